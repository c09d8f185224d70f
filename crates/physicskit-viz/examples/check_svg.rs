//! Runs the layout checks on SVG files and renders each to a PNG beside it (resvg, twice the
//! figure's size), for looking at figures without a browser:
//! `cargo run --example check_svg -p physicskit-viz -- FILE.svg ...`.

use std::path::Path;

fn main() {
    let mut failed = false;
    for arg in std::env::args().skip(1) {
        let path = Path::new(&arg);
        let svg = match std::fs::read_to_string(path) {
            Ok(s) => s,
            Err(e) => {
                eprintln!("{arg}: {e}");
                failed = true;
                continue;
            }
        };
        match physicskit_viz::layout::check(&svg, path) {
            Ok(problems) => {
                for p in &problems {
                    println!("{arg}: {p}");
                }
                failed |= !problems.is_empty();
            }
            Err(e) => {
                eprintln!("{arg}: {e}");
                failed = true;
            }
        }
        match physicskit_viz::svg::rasterize(&svg, 2.0, path) {
            Ok(pixmap) => {
                let out = path.with_extension("png");
                if let Err(e) = pixmap.save_png(&out) {
                    eprintln!("{}: {e}", out.display());
                    failed = true;
                }
            }
            Err(e) => {
                eprintln!("{arg}: {e}");
                failed = true;
            }
        }
    }
    std::process::exit(i32::from(failed));
}
