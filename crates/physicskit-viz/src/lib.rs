//! # physicskit-viz
//!
//! Figures and animations of the physicskit demonstrations, drawn with
//! [plotters](https://docs.rs/plotters) into PNG files and animated GIFs, with the DejaVu Sans
//! font embedded (no system font is needed; see [`font`]).
//!
//! * [`figure`]: line/dot panels with titles, axis labels with units and legends; multi-panel
//!   PNG files.
//! * [`heatmap`]: space–time heat maps with a colour bar.
//! * [`animation`]: animated GIFs.
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

pub use error::{Result, VizError};
pub use gallery::{demo_count, render_gallery, Demo, GalleryFile, GalleryReport};
