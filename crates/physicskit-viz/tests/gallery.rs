//! Renders the whole gallery in quick mode into a temporary directory and checks every promised
//! file: it exists, has a sensible size, is not blank, every GIF is animated, and every SVG
//! figure passes the layout checks of `physicskit_viz::layout` (text inside the figure, no two
//! text boxes overlapping, no legend over its own data).

use std::fs::File;
use std::path::{Path, PathBuf};

/// A fresh directory under the system temp dir, removed at the end of the test.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        Self(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn variance(v: &[f64]) -> f64 {
    let n = v.len() as f64;
    let mean = v.iter().sum::<f64>() / n;
    v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / n
}

/// Frames of a GIF and the luminance variance of its last frame.
fn gif_frames(path: &Path) -> (usize, f64) {
    let mut opts = gif::DecodeOptions::new();
    opts.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = opts.read_info(File::open(path).unwrap()).unwrap();
    let mut frames = 0;
    let mut last_var = 0.0;
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        frames += 1;
        let luma: Vec<f64> = frame
            .buffer
            .chunks_exact(4)
            .map(|p| 0.299 * f64::from(p[0]) + 0.587 * f64::from(p[1]) + 0.114 * f64::from(p[2]))
            .collect();
        last_var = variance(&luma);
    }
    (frames, last_var)
}

/// The lab's caption of each system (the `physics` field of the catalogue JSON the lab is
/// handed, `physicskit_listing::catalogue_json`) is the paragraph the gallery printed for the
/// demonstration showing that system, if one does, and every demonstration's paragraph that
/// maps to a system reaches the lab (the integrators demonstration through the pendulum it
/// integrates).
fn lab_captions_are_the_gallery_paragraphs(demos: &[physicskit_viz::Demo], html: &str) {
    let json: serde_json::Value =
        serde_json::from_str(&physicskit_listing::catalogue_json()).expect("catalogue JSON");
    let systems = json["systems"].as_array().expect("systems");
    let mut captioned = 0;
    for s in systems {
        let name = s["name"].as_str().unwrap();
        let Some(caption) = s["physics"].as_str() else {
            continue;
        };
        captioned += 1;
        // A system the gallery shows has its demonstration's paragraph as the lab's caption
        // (some systems, the newest, have a catalogue paragraph but no demonstration yet).
        if let Some(demo) = demos.iter().find(|d| d.explanation == caption) {
            assert!(
                html.contains(&format!("id=\"{}\"", demo.slug)),
                "index.html has no section {} for {name}",
                demo.slug
            );
        }
    }
    for d in demos {
        let explanation =
            physicskit::classical::explanations::for_demo(&d.slug).expect("an explanation");
        if explanation.system().is_none() {
            continue; // an analysis across systems, captioned by their own demonstrations
        }
        assert!(
            systems
                .iter()
                .any(|s| s["physics"].as_str() == Some(d.explanation.as_str())),
            "no lab caption carries the paragraph of {}",
            d.slug
        );
    }
    // Every catalogue system but the harmonic oscillator has a physics paragraph.
    assert_eq!(captioned, systems.len() - 1, "captioned systems");
}

#[test]
fn quick_gallery_renders_every_promised_file() {
    let dir = TempDir::new("physicskit-gallery");
    let mut messages = Vec::new();
    let report =
        physicskit_viz::render_gallery(&dir.0, true, &mut |m: &str| messages.push(m.to_string()))
            .expect("gallery renders");

    // Every demonstration (the list in gallery/mod.rs), each announced to the progress
    // callback, each with a paragraph of physics and at least one file, under its own anchor.
    let count = physicskit_viz::demo_count();
    assert!(count >= 14, "{count} demonstrations");
    assert_eq!(report.demos.len(), count);
    assert_eq!(messages.len(), count);
    let mut slugs: Vec<&str> = report.demos.iter().map(|d| d.slug.as_str()).collect();
    slugs.sort_unstable();
    slugs.dedup();
    assert_eq!(slugs.len(), count, "duplicate anchors");
    for d in &report.demos {
        assert!(!d.files.is_empty(), "{} has no file", d.title);
        assert!(
            d.explanation.len() > 200,
            "{} explanation too short",
            d.title
        );
    }
    let html = std::fs::read_to_string(&report.index).unwrap();
    // Every demonstration prints its figures' setup after the physics (the lab's caption
    // omits it, as the lab runs any setting).
    for d in &report.demos {
        assert!(!d.figure.is_empty(), "{} has no setup", d.slug);
    }
    assert_eq!(html.matches("<p class=\"setup\">").count(), count);
    // Demonstration k (its place in the list) is titled "k. ..." and its files are named
    // "kk_...", each number written once (a page that typed its own would show it twice).
    for (k, d) in report.demos.iter().enumerate() {
        let title = d.title.strip_prefix(&format!("{}. ", k + 1));
        assert!(
            title.is_some_and(|t| !t.starts_with(|c: char| c.is_ascii_digit())),
            "demonstration {} is titled {:?}",
            k + 1,
            d.title
        );
        for f in &d.files {
            let name = f.path.file_name().unwrap().to_string_lossy();
            let rest = name.strip_prefix(&format!("{:02}_", k + 1));
            assert!(
                rest.is_some_and(|r| !r.starts_with(|c: char| c.is_ascii_digit())),
                "demonstration {} wrote {name}",
                k + 1
            );
        }
    }
    assert!(html.contains(&format!(">{count} demonstrations of")));
    lab_captions_are_the_gallery_paragraphs(&report.demos, &html);
    let mut gifs = 0;
    let mut problems = Vec::new();
    for f in &report.files {
        assert!(f.path.starts_with(&dir.0));
        assert!(!f.description.is_empty());
        let size = std::fs::metadata(&f.path).map(|m| m.len()).unwrap_or(0);
        let name = f.path.file_name().unwrap().to_string_lossy().to_string();
        match f.path.extension().and_then(|e| e.to_str()) {
            Some("svg") => {
                // A figure with axes, text and data is several kB (a blank one about 1 kB); keep each below 3 MB so the
                // page stays light (dense Poincaré sections are the largest).
                assert!((4_000..3_000_000).contains(&size), "{name}: {size} bytes");
                let svg = std::fs::read_to_string(&f.path).unwrap();
                // Not blank: some data group or image with drawn content, or the curves of a
                // figure drawn as SVG paths of its own (the polhode sphere).
                assert!(
                    svg.contains("<g class=\"pk-data\"")
                        || svg.contains("<image ")
                        || svg.matches("<polygon").count() > 3
                        || svg.matches("<path").count() > 3,
                    "{name}: no plotted data"
                );
                assert!(html.contains(&name), "index.html does not show {name}");
                for p in physicskit_viz::layout::check(&svg, &f.path).expect("SVG parses") {
                    problems.push(format!("{name}: {p}"));
                }
            }
            Some("gif") => {
                gifs += 1;
                assert!((10_000..5_000_000).contains(&size), "{name}: {size} bytes");
                let (frames, var) = gif_frames(&f.path);
                assert!(frames > 1, "{name}: {frames} frame(s)");
                assert!(var > 100.0, "{name}: last frame variance {var}");
                assert!(html.contains(&name), "index.html does not show {name}");
            }
            Some("html") => assert!(size > 1000),
            other => panic!("unexpected file type {other:?} for {name}"),
        }
    }
    assert!(
        problems.is_empty(),
        "layout problems:\n{}",
        problems.join("\n")
    );
    // The issue promises animations for the double pendulum, the swarm, the sine-Gordon chain
    // and the Euler top.
    assert!(gifs >= 4, "{gifs} GIFs");
    // Every file on disk is reported, and nothing else was written.
    let on_disk = std::fs::read_dir(&dir.0).unwrap().count();
    assert_eq!(on_disk, report.files.len());
}

#[test]
fn unwritable_output_directory_is_an_error() {
    let dir = TempDir::new("physicskit-gallery-file");
    std::fs::write(&dir.0, b"not a directory").unwrap();
    let err = physicskit_viz::render_gallery(&dir.0.join("sub"), true, &mut |_: &str| {});
    assert!(
        matches!(err, Err(physicskit_viz::VizError::Io { .. })),
        "{err:?}"
    );
    let _ = std::fs::remove_file(&dir.0);
}
