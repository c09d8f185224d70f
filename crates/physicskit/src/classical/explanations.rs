//! The gallery's paragraphs: one per demonstration, keyed by its slug.
//!
//! A demonstration of a system opens with that system's physics, which its catalogue entry
//! holds ([`SystemEntry::physics`], written next to the system and shown by the lab and
//! `list --json` too); a demonstration of a method or of an analysis across systems has a
//! paragraph of its own here. Each then says what the gallery's figures show (their
//! parameters, grid sizes, run times and panels), which only the gallery prints: the physics
//! holds for any parameters, and states no number of the figure part
//! (`tests/classical/explanations.rs`). The gallery (`physicskit-viz`) prints
//! [`for_demo`]`(slug)` under each demonstration.

use crate::classical::model::SystemEntry;
use crate::classical::systems;

/// One demonstration's paragraph.
#[derive(Debug, Clone, Copy)]
pub struct Explanation {
    /// The gallery demonstration's anchor name, e.g. `"double-pendulum"`.
    pub slug: &'static str,
    /// The physics part: a system's, or the demonstration's own.
    pub text: Text,
    /// What the gallery's figures show: their parameters, grid sizes, run times and panels
    /// (never empty). The gallery prints it after the physics; the lab, which starts from the
    /// catalogue's defaults, does not.
    pub figure: &'static str,
}

/// Where a demonstration's physics paragraph comes from.
#[derive(Debug, Clone, Copy)]
pub enum Text {
    /// The physics of the catalogue system the demonstration shows.
    OfSystem(&'static SystemEntry),
    /// A paragraph of the demonstration's own (a method, or an analysis across systems).
    Own(&'static str),
}

impl Explanation {
    /// The physics paragraph (plain text, Unicode), true whatever the parameters.
    pub fn text(&self) -> &'static str {
        match self.text {
            Text::OfSystem(entry) => entry.physics.unwrap_or(""),
            Text::Own(text) => text,
        }
    }

    /// The catalogue system whose physics opens the paragraph, if any.
    pub fn system(&self) -> Option<&'static SystemEntry> {
        match self.text {
            Text::OfSystem(entry) => Some(entry),
            Text::Own(_) => None,
        }
    }
}

/// The paragraph of the gallery demonstration `slug`, if there is one.
pub fn for_demo(slug: &str) -> Option<&'static Explanation> {
    EXPLANATIONS.iter().find(|e| e.slug == slug)
}

/// Every explanation, in gallery order.
pub static EXPLANATIONS: &[Explanation] = &[
    Explanation {
        slug: "double-pendulum",
        text: Text::OfSystem(&systems::DOUBLE_PENDULUM_ENTRY),
        figure:
            "Rods of 1 m with 1 kg bobs (g = 9.81 m/s²) released from 115° and 138°; the second \
         run starts 10⁻⁹ rad away; the integrators are the implicit midpoint rule and rk4.",
    },
    Explanation {
        slug: "henon-heiles",
        text: Text::OfSystem(&systems::HENON_HEILES_ENTRY),
        figure: "Each colour is one orbit; the three panels are at E = 1/12 (almost everything \
         regular), E = 1/8 (islands in a chaotic sea) and the saddles' energy.",
    },
    Explanation {
        slug: "swarm",
        text: Text::OfSystem(&systems::SWARM_ENTRY),
        figure:
            "g/l = 1 s⁻²; the patch starts just inside the separatrix, and its area is measured \
         on 2000 boundary points carried along with the flow.",
    },
    Explanation {
        slug: "fput",
        text: Text::OfSystem(&systems::FPUT_ENTRY),
        figure: "32 masses; the figure follows the energies of the lowest modes.",
    },
    Explanation {
        slug: "sine-gordon",
        text: Text::OfSystem(&systems::SINE_GORDON_KINK_ENTRY),
        figure: "The kink and the antikink approach each other at 0.4 of the wave speed.",
    },
    Explanation {
        slug: "chains",
        text: Text::OfSystem(&systems::HARMONIC_CHAIN_ENTRY),
        figure:
            "The first figure shows the shapes of the four lowest modes of an 8-mass chain, each \
         checked by simulation (the dots are the displacements half a period later, flipped \
         in sign as a standing wave must be). The second shows beats in a 12-mass chain \
         started in a superposition of its two highest modes (ω₁₁ and ω₁₂).",
    },
    Explanation {
        slug: "kepler",
        text: Text::OfSystem(&systems::KEPLER_ENTRY),
        figure: "Units with G M = 1; semi-major axis 1, eccentricity 0.6.",
    },
    Explanation {
        slug: "euler-top",
        text: Text::OfSystem(&systems::EULER_TOP_ENTRY),
        figure: "I₁ = 1, I₂ = 2, I₃ = 3 (a flat plate), spun almost exactly about axis 2.",
    },
    Explanation {
        slug: "heavy-top",
        text: Text::OfSystem(&systems::HEAVY_TOP_ENTRY),
        figure:
            "I₁ = 1, I₃ = 0.5 kg m², M g l = 9.81 J, started with a small backward precession: \
         the tip draws loops.",
    },
    Explanation {
        slug: "hoop",
        text: Text::OfSystem(&systems::HOOP_ENTRY),
        figure: "R = 1 m, g = 9.81 m/s², ω up to 2.5 ω_c; the phase portraits are at ω = 0.7 ω_c \
         and 1.6 ω_c.",
    },
    Explanation {
        slug: "projectile",
        text: Text::OfSystem(&systems::PROJECTILE_ENTRY),
        figure: "A 1 kg ball launched at 40 m/s; with drag its terminal speed is 22 m/s.",
    },
    Explanation {
        slug: "integrators",
        text: Text::OfSystem(&crate::classical::examples::PENDULUM_ENTRY),
        figure:
            "The same pendulum (released from 115°, g/l = 1 s⁻²) integrated with the four methods \
         of the specification, and the convergence plot of their errors.",
    },
    Explanation {
        slug: "toda",
        text: Text::OfSystem(&systems::TODA_ENTRY),
        figure: "Sixteen masses, a = b = 1; two particles are kicked with 3 and −1.5 units of \
         momentum. Left: the energy of each particle above its equilibrium share a/b; middle: \
         two particles; right: the sixteen eigenvalues of L, flat lines.",
    },
    Explanation {
        slug: "elastic-pendulum",
        text: Text::OfSystem(&systems::ELASTIC_PENDULUM_ENTRY),
        figure:
            "A 1 kg bob, rest length 1 m, g = 9.81 m/s², pulled 10 cm below its hanging position \
         and let go with a 1° swing: at the resonance, k = 29.43 N/m (r_eq = 4/3 m), the \
         energy passes to the swing; at k = 40 N/m (ω_s/ω_p = 2.25, close to the quoted rule) \
         the same start keeps bouncing with a swing that never grows.",
    },
    Explanation {
        slug: "flip-fractal",
        text: Text::Own(
            "Each pixel is one double pendulum released from rest at the angles (θ₁, θ₂); its \
         colour is the time until either arm first swings over the top (|θ| > π), located \
         inside the integration step. Energy alone forbids a flip where the energy at rest is \
         at or below the flip energy, that of the lowest state with an arm upside down (for \
         point bobs min(g₁ − |g₂|, g₂ − |g₁|), with g₁ = (m₁ + m₂) g l₁ and g₂ = m₂ g l₂: the \
         library's DoublePendulumParams::flip_energy). No member inside the black curve can \
         flip; those and the members that did not flip within the run are drawn at the top of \
         the scale. The boundaries between flip times are fractal (Heyl 2008): nearby starts \
         that straddle them flip at very different times, the fingerprint of chaos. Computed as \
         one ensemble on all cores (physicskit::classical::ensemble), bit-identical for any \
         number of threads.",
        ),
        figure: "Equal masses and arms (1 kg, 1 m, g = 9.81 m/s²), for which the curve is 2 cos \
         θ₁ + cos θ₂ = 1 (Heyl's 3 cos θ₁ + cos θ₂ = 2 is for uniform rods); 240 × 240 starts \
         run for 30 s with rk4 at dt = 0.01 s; times in units of √(l/g).",
    },
    Explanation {
        slug: "kepler-precession",
        text: Text::Own(
            "An ensemble of Kepler orbits with the post-Newtonian term c_pn/r³ added to the \
         potential −k/r, swept over a range of strengths. For each member the direction of the \
         Laplace–Runge–Lenz vector is followed along the run and its mean turning rate times \
         the orbital period gives the precession per orbit (dots). First-order perturbation \
         theory (Landau & Lifshitz §15) predicts Δφ = −6π c_pn μ² k / L⁴ per orbit (line): the \
         two agree for weak corrections and part at second order in c_pn.",
        ),
        figure: "Forty orbits of semi-major axis a = 1 and eccentricity e = 0.5 in units with μ = \
         k = 1, c_pn from −0.00025 to −0.01, each run for 20 periods with yoshida4 at 4000 \
         steps per period.",
    },
    Explanation {
        slug: "henon-heiles-regular-fraction",
        text: Text::Own(
            "How much of the Hénon–Heiles energy surface is regular, energy by energy. At \
         each energy E a grid of starts fills the surface of section x = 0 inside its \
         zero-velocity curve (p_x ≥ 0 from the energy); each start is one ensemble member whose \
         SALI (the smaller alignment index of two deviation vectors, Skokos 2001) is computed \
         on all cores. An orbit on an invariant torus keeps SALI away from zero; a chaotic one \
         drives it below the library's threshold of 10⁻⁸. The fraction of regular starts \
         estimates the relative area of the section covered by invariant curves, the quantity \
         Hénon & Heiles (1964) plotted against E: close to one up to about E = 0.11, then \
         falling steeply as the tori break up, with only small islands left near the escape \
         energy 1/6. A chaotic orbit that has not yet shown its chaos by the end of the run \
         counts as regular, so the curve is an upper estimate that longer runs lower.",
        ),
        figure: "Eleven energies from 1/24 to 0.16; at each, the cells of a 60 × 60 grid over the \
         energy curve's extent that lie inside it, each run to t = 3000 with yoshida4 at dt = \
         0.1.",
    },
    Explanation {
        slug: "work-precision",
        text: Text::Own(
            "How much accuracy each integrator buys per evaluation of the forces, the cost \
         Hairer, Nørsett and Wanner count in their work–precision diagrams: unlike a wall \
         time, the count is the same on every machine and every run. Each line is one \
         method, each point one step size (halved from point to point) or, for the adaptive \
         DOP853, one tolerance (tenfold apart); lower left is better. On the Kepler orbit (the \
         error is the phase lag after the run against the analytic orbit) and on Hénon–Heiles \
         (the largest energy error over the run), the high-order symplectic compositions \
         (Kahan and Li's of order eight, Sofroniou and Spaletta's of order ten) reach the \
         rounding floor at a small fraction of the cost of Störmer–Verlet or Yoshida's \
         fourth-order method, whose lines are steep but start far up. On the double \
         pendulum, a chaotic Lagrangian system where only the methods for non-separable systems \
         apply, the Gauss–Legendre methods of order 4 and 6 reach a given error at far lower \
         cost than the second-order implicit midpoint rule, whose fixed-point solve takes more \
         sweeps per step the larger the step.",
        ),
        figure: "Kepler at eccentricity e = 0.5 (a = k = μ = 1) over 100 orbits from perihelion; \
         SciML's Hénon–Heiles case, q = (0.1, 0) and p = (0, 0.5), to t = 1000; the double \
         pendulum with unit masses and arms from θ = (2, 1) rad and θ̇ = (0.5, −0.3) rad/s to t \
         = 10 s, against a DOP853 reference run.",
    },
    Explanation {
        slug: "henon-heiles-sali",
        text: Text::Own(
            "The Hénon–Heiles system at one energy seen two ways on the same plane, the \
         section x = 0 with pₓ > 0 (pₓ fixed by the energy; the blank corners lie outside the \
         energy surface). Left, the Poincaré section: regular orbits draw closed curves, \
         sections of invariant tori, around the islands; chaotic ones scatter dots over a sea. \
         Right, every cell is one orbit started there, coloured by its Smaller Alignment Index \
         (Skokos 2001) at the end of the run: two deviation vectors follow the tangent dynamics \
         (the exact tangent map of the splitting step) and SALI measures how nearly they have \
         aligned. On a chaotic orbit both turn towards the most unstable direction and SALI \
         falls exponentially, as exp(−(λ₁ − λ₂)t); on a torus they stay apart and SALI stays of \
         order 0.1–1. Below the library's threshold of 10⁻⁸ (dark) an orbit is called chaotic; \
         the map draws the islands of the section in one run per cell, without following any \
         orbit by eye. Sticky orbits, which cling to an island's edge for a long time, have not \
         fallen below the threshold yet and show as intermediate colours.",
        ),
        figure: "E = 1/8; a 100 × 100 grid of starts run to t = 1000 with yoshida4 at dt = 0.05; \
         the section's 24 orbits cross the plane 800 times each.",
    },
    Explanation {
        slug: "double-pendulum-lyapunov",
        text: Text::Own(
            "Each pixel is one double pendulum released from rest at the angles (θ₁, θ₂), \
         coloured by its largest Lyapunov exponent: the growth rate, per second, of an \
         infinitesimal deviation carried by the tangent dynamics (Benettin's method, the \
         finite-time value at the end of the run). Inside the white curve the energy at rest is \
         at or below the flip energy, that of the lowest state with an arm upside down (the \
         library's DoublePendulumParams::flip_energy), so neither arm can ever flip: there the \
         map is dark, small exponents of mostly regular motion (a finite run leaves a residue \
         of order ln(t)/t even on a torus). Starts that the energy would let flip may still \
         stay on regular tori and extend the dark region beyond the curve. Further out the map \
         is a speckle of chaotic starts, the same structure the flip-time fractal shows in its \
         boundaries. The map has the pendulum's symmetry (θ₁, θ₂) → (−θ₁, −θ₂) up to the finite \
         run. Computed with the library's chaos map on all cores, bit-identical for any number \
         of threads.",
        ),
        figure: "Equal masses and arms (1 kg, 1 m, g = 9.81 m/s²), for which the curve is 2 cos \
         θ₁ + cos θ₂ = 1; 100 × 100 starts run to t = 20 s with rk4 at dt = 0.01 s, the \
         deviation renormalized every 10 steps. The dark region reaches beyond the curve in two \
         arms; the chaotic starts have exponents of one to two per second.",
    },
    Explanation {
        slug: "hoop-pitchfork",
        text: Text::Own(
            "The bead on the rotating hoop as a bifurcation diagram. Left: the equilibria at \
         rest against the rotation rate ω, from the library's analysis of V_eff = −R²ω² sin²θ/2 \
         + gR(1 − cos θ): the bottom is stable up to ω_c = √(g/R), then gives way to the pair \
         θ* = ±arccos(g/(Rω²)); the top is always unstable. Right: the largest Lyapunov \
         exponent at the bottom. Linearized about θ = 0 the motion is x'' = (ω² − g/R)x: a \
         centre below ω_c, with exponent zero, and a saddle above it, whose deviations grow as \
         exp(t√(ω² − g/R)) (line). The orbit resting exactly at the bottom has these tangent \
         dynamics, and its measured finite-time exponent follows the line, crossing zero at \
         ω_c; below ω_c it scatters about zero by the 1/t of a bounded rotation. An orbit \
         started slightly off the bottom is different: with one degree of freedom every orbit \
         lies on a regular curve, here a libration about one of the new minima that passes \
         close to the saddle. Over a short window near the saddle its deviations grow at the \
         saddle's rate, but over a long run they only grow linearly, and its exponent tends to \
         zero like ln(t)/t: the hoop is not chaotic, the exponent at the bottom measures the \
         instability of the equilibrium.",
        ),
        figure: "R = 1 m, g = 9.81 m/s², ω up to 2.5 ω_c; implicit midpoint at dt = 0.001 s; the \
         orbit at rest at the bottom (orange dots) run for 10 s, the one started 0.01 rad from \
         it (green dots) for 200 s.",
    },
    Explanation {
        slug: "foucault",
        text: Text::OfSystem(&systems::FOUCAULT_ENTRY),
        figure: "A 67 m pendulum (g = 9.81 m/s²) released at rest 3 m east of the vertical; \
         implicit midpoint at dt = 0.05 s. Left, Earth's rate is raised so that the plane turns \
         once in 40 swings; right, the Panthéon's latitude 48.85° N and Earth's sidereal rate.",
    },
    Explanation {
        slug: "rolling-rattleback",
        text: Text::OfSystem(&systems::ROLLING_RATTLEBACK_ENTRY),
        figure: "Kane and Levinson's body (semi-axes 0.2, 0.03 and 0.02 m, 1 kg, principal axes \
         turned from the geometric ones) started tilted 0.5° in roll and pitch and spun at \
         −5 and +5 rad/s; rk4 at dt = 10⁻⁴ s, no slip and no dissipation.",
    },
];
