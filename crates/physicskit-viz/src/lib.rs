//! # physicskit-viz
//!
//! Figures and animations of the physicskit demonstrations: SVG figures drawn with
//! [plotters](https://docs.rs/plotters) and this crate's own data, legend and colour-bar
//! elements, text set in the bundled DejaVu Sans (see [`font`]); animated GIFs rendered from
//! the same SVG drawing by [resvg](https://docs.rs/resvg).
//!
//! * [`figure`]: line/dot panels with wrapped titles, axis labels with units and legends placed
//!   where they hide no data; multi-panel SVG files.
//! * [`heatmap`]: heat maps with a colour bar.
//! * [`animation`]: animated GIFs.
//! * [`layout`]: the checks every gallery figure passes (text inside the figure and apart,
//!   legends off the data).
//! * [`gallery`]: the demonstrations and [`render_gallery`], which writes them all and
//!   an offline `index.html` explaining the physics of each.
//!
//! All physics comes from the `physicskit` crate; this crate only simulates through its public
//! API and draws.

pub mod animation;
pub mod error;
pub mod figure;
pub mod font;
pub mod gallery;
pub mod heatmap;
mod html;
pub mod layout;
pub mod svg;
pub mod text;

pub use error::{Result, VizError};
pub use gallery::{
    demo_count, explanations, render_demo, render_gallery, Demo, Explanation, GalleryFile,
    GalleryReport, LabLink, LabSetup, Physics,
};
