//! Renders the gallery: `cargo run --release -p physicskit-viz --example gallery -- [DIR] [--quick]`.

use std::path::PathBuf;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = args.iter().any(|a| a == "--quick");
    let dir = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("gallery"));
    let mut last = Instant::now();
    let mut progress = |msg: &str| {
        eprintln!("{:6.2} s  {msg}", last.elapsed().as_secs_f64());
        last = Instant::now();
    };
    match physicskit_viz::render_gallery(&dir, quick, &mut progress) {
        Ok(report) => {
            for f in &report.files {
                println!("{}: {}", f.path.display(), f.description);
            }
            println!(
                "rendered {} files in {:.1} s",
                report.files.len(),
                report.seconds
            );
        }
        Err(e) => {
            eprintln!("error: {e}");
            std::process::exit(1);
        }
    }
}
