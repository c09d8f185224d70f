//! Every built-in system against analytic solutions, conserved quantities, perturbation theory
//! and hand-derived forces; one test per validation error.

mod chains;
mod double_pendulum;
mod elastic_pendulum;
mod henon_heiles;
mod hoop;
mod kepler;
mod lagrangian;
mod params_defaults;
mod projectile;
mod reduced_models;
mod rigid_body;
mod rolling;
mod sizes;
mod swarm;
mod symmetric_top;
mod toda;
mod triple_pendulum;
mod validation;
