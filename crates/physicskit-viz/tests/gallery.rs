//! Renders the whole gallery in quick mode into a temporary directory and checks every promised
//! file: it exists, has a sensible size, is not blank, every GIF is animated, and every SVG
//! figure passes the layout checks of `physicskit_viz::layout` (text inside the figure, no two
//! text boxes overlapping, no legend over its own data).

use std::collections::BTreeMap;
use std::fs::File;
use std::path::{Path, PathBuf};

use physicskit::classical::catalog;
use physicskit::classical::model::entry::{ParamKind, Value};
use physicskit::classical::Method;

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
        let explanation = physicskit_viz::gallery::explanations()
            .find(|e| e.slug == d.slug)
            .expect("an explanation");
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

/// A share-link value percent-decoded, as `URLSearchParams` decodes it.
fn url_decode(s: &str) -> String {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'%' => {
                let hex = std::str::from_utf8(&b[i + 1..i + 3]).expect("two hex digits");
                out.push(u8::from_str_radix(hex, 16).expect("hex"));
                i += 3;
            }
            b'+' => {
                out.push(b' ');
                i += 1;
            }
            c => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8(out).expect("UTF-8")
}

/// A JSON value of a share link's parameters as the catalogue value of the parameter's kind,
/// as the lab converts it (`physicskit-wasm`, `values_from_json`).
fn value_of(kind: ParamKind, json: &serde_json::Value) -> Value {
    match (kind, json) {
        (ParamKind::Integer, serde_json::Value::Number(n)) => {
            Value::Integer(n.as_i64().expect("an integer"))
        }
        (ParamKind::Scalar, serde_json::Value::Number(n)) => Value::Scalar(n.as_f64().unwrap()),
        (ParamKind::Vector(_), serde_json::Value::Array(xs)) => {
            Value::Vector(xs.iter().map(|x| x.as_f64().expect("a number")).collect())
        }
        (ParamKind::Choice(_), serde_json::Value::String(w)) => Value::Choice(w.clone()),
        (kind, json) => panic!("{json} is no {}", kind.name()),
    }
}

/// Every demonstration's "Open in the lab" link, read back from its URL fragment alone: the
/// system, method and step are the demonstration's, its parameters are the values the
/// demonstration ran with (numbers bit for bit), and the catalogue entry built from them, as
/// the lab builds it, starts from the demonstration's initial state bit for bit (the link's
/// `state` field included, when it carries one) and takes a step with the link's method and
/// dt. Whether the page itself accepts each link is checked in Chromium (web/test/gallery.mjs).
fn lab_links_read_back_to_the_runs(demos: &[physicskit_viz::Demo]) -> usize {
    let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let mut linked = 0;
    for d in demos {
        let Some(link) = &d.lab else { continue };
        linked += 1;
        let setup = &link.setup;
        let fields: BTreeMap<String, String> = link
            .hash
            .strip_prefix('#')
            .expect("a fragment")
            .split('&')
            .map(|kv| {
                let (k, v) = kv.split_once('=').expect("key=value");
                (url_decode(k), url_decode(v))
            })
            .collect();
        let slug = &d.slug;
        assert_eq!(fields["system"], setup.system, "{slug}");
        assert_eq!(fields["method"], setup.method.name(), "{slug}");
        let method: Method = fields["method"].parse().expect("a method name");
        let dt: f64 = fields["dt"].parse().expect("dt");
        assert_eq!(dt.to_bits(), setup.dt.to_bits(), "{slug}: dt");
        let entry = catalog::find(&fields["system"]).expect("a catalogue system");
        let json: serde_json::Value = serde_json::from_str(&fields["params"]).expect("JSON");
        let mut params: Vec<(String, Value)> = json
            .as_object()
            .expect("a JSON object")
            .iter()
            .map(|(k, v)| {
                let kind = entry
                    .param(k)
                    .unwrap_or_else(|| panic!("{slug}: no {k}"))
                    .kind;
                (k.clone(), value_of(kind, v))
            })
            .collect();
        let mut expected = setup.params.clone();
        params.sort_by(|a, b| a.0.cmp(&b.0));
        expected.sort_by(|a, b| a.0.cmp(&b.0));
        let as_bits = |ps: &[(String, Value)]| {
            ps.iter()
                .map(|(k, v)| {
                    let b = match v {
                        Value::Scalar(x) => vec![x.to_bits()],
                        Value::Vector(xs) => bits(xs),
                        Value::Integer(i) => vec![*i as u64],
                        Value::Choice(c) => c.bytes().map(u64::from).collect(),
                    };
                    (k.clone(), b)
                })
                .collect::<Vec<_>>()
        };
        assert_eq!(as_bits(&params), as_bits(&expected), "{slug}: parameters");
        let mut system = entry.build_from(params).expect("the entry builds");
        if let Some(state) = fields.get("state") {
            let state: Vec<f64> = state.split(',').map(|x| x.parse().unwrap()).collect();
            system
                .reset(Some(&state), 0.0)
                .expect("a state of the system");
        }
        assert_eq!(
            bits(system.dynamical().state()),
            bits(&setup.start),
            "{slug}: the lab would start elsewhere than the demonstration"
        );
        system
            .integrate((0.0, dt), dt, method, Default::default())
            .unwrap_or_else(|e| panic!("{slug}: one step: {e}"));
    }
    linked
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
    // Every demonstration whose main run is one run of a catalogue system links it; these
    // are the ones without a single run to open: maps and sweeps over many starts or
    // parameters, and comparisons of methods.
    const MANY_RUNS: [&str; 7] = [
        "flip-fractal",
        "kepler-precession",
        "work-precision",
        "henon-heiles-sali",
        "double-pendulum-lyapunov",
        "hoop-pitchfork",
        "henon-heiles-regular-fraction",
    ];
    let linked = lab_links_read_back_to_the_runs(&report.demos);
    for d in &report.demos {
        assert_eq!(
            d.lab.is_none(),
            MANY_RUNS.contains(&d.slug.as_str()),
            "{}: lab link {:?}",
            d.slug,
            d.lab.as_ref().map(|l| &l.hash)
        );
    }
    assert_eq!(linked, count - MANY_RUNS.len());
    // The page carries each link (its fragment, HTML-escaped).
    for link in report.demos.iter().filter_map(|d| d.lab.as_ref()) {
        let href = format!("href=\"lab/index.html{}\"", link.hash.replace('&', "&amp;"));
        assert!(html.contains(&href), "index.html lacks {href}");
    }
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

/// The work–precision figure counts its cost (force evaluations) instead of timing it: two
/// renders are byte for byte the same, and every method's line runs one way along the cost
/// axis (a timed axis doubled back under load).
#[test]
fn work_precision_is_reproducible_and_monotone_in_cost() {
    const WORK_PRECISION: usize = 17;
    let a = TempDir::new("physicskit-wp-a");
    let b = TempDir::new("physicskit-wp-b");
    let demo = physicskit_viz::render_demo(&a.0, WORK_PRECISION, true).unwrap();
    assert_eq!(
        demo.slug, "work-precision",
        "demonstration {WORK_PRECISION} moved"
    );
    physicskit_viz::render_demo(&b.0, WORK_PRECISION, true).unwrap();
    assert_eq!(demo.files.len(), 3, "one figure per problem");
    for file in &demo.files {
        let name = file.path.file_name().unwrap();
        let first = std::fs::read(&file.path).unwrap();
        let second = std::fs::read(b.0.join(name)).unwrap();
        assert!(first == second, "{name:?} differs between two renders");
        let svg = String::from_utf8(first).unwrap();
        let doc = resvg::usvg::roxmltree::Document::parse(&svg).unwrap();
        let lines: Vec<Vec<(f64, f64)>> = doc
            .descendants()
            .filter(|n| n.attribute("class") == Some("pk-data"))
            .flat_map(|g| g.children().filter(|n| n.has_tag_name("path")))
            .filter_map(|p| p.attribute("d"))
            .filter(|d| d.contains('L'))
            .flat_map(physicskit_viz::layout::path_points)
            .collect();
        // Five methods integrate the double pendulum (those for non-separable systems), more
        // the separable problems: a line each.
        assert!(lines.len() >= 5, "{name:?}: {} lines", lines.len());
        for line in &lines {
            assert!(
                line.windows(2).all(|s| s[1].0 > s[0].0),
                "{name:?}: a line doubles back along the cost axis: {line:?}"
            );
        }
    }
    let none = physicskit_viz::render_demo(&a.0, 0, true);
    assert!(
        matches!(none, Err(physicskit_viz::VizError::NoDemo(0, _))),
        "{none:?}"
    );
}
