//! Layout checks of a figure, read from its SVG alone:
//!
//! * every text element's box lies inside the viewport;
//! * no two text boxes overlap;
//! * no legend box (`<g class="pk-legend">`) covers a plotted point or line segment of its own
//!   axes (the `<g class="pk-data">` groups with the same `data-axes` rectangle).
//!
//! Text boxes are resvg's (usvg's) layout of each text element in the bundled DejaVu Sans: the
//! advance width of the shaped string by the font's ascent-to-descent height, turned with the
//! element (rotated axis labels). A browser falling back to another sans-serif face sets
//! narrower text (see [`crate::svg::FONT_STACK`]).

use std::fmt;
use std::path::Path;

use resvg::usvg::{self, roxmltree};

use crate::error::{Result, VizError};
use crate::figure::Rect;

/// Boxes may touch or overlap by this much (pixels) without counting: half a pixel is below
/// what a reader sees and absorbs rounding of the coordinates in the file (two decimals).
const SLACK: f64 = 0.5;

/// One broken rule.
#[derive(Debug, Clone, PartialEq)]
pub enum Problem {
    /// A text element reaches past the viewport.
    TextOutside {
        /// The text.
        text: String,
        /// Its box `(x0, y0, x1, y1)`.
        bbox: (f64, f64, f64, f64),
    },
    /// Two text elements overlap.
    TextOverlap {
        /// The first text.
        a: String,
        /// The second text.
        b: String,
    },
    /// A legend covers a plotted point of its own axes.
    LegendOverData {
        /// The legend's first entry.
        legend: String,
        /// The covered point, in pixels.
        point: (f64, f64),
    },
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Problem::TextOutside { text, bbox } => write!(
                f,
                "text {text:?} at ({:.1}, {:.1})–({:.1}, {:.1}) reaches past the viewport",
                bbox.0, bbox.1, bbox.2, bbox.3
            ),
            Problem::TextOverlap { a, b } => write!(f, "texts {a:?} and {b:?} overlap"),
            Problem::LegendOverData { legend, point } => write!(
                f,
                "the legend starting {legend:?} covers the plotted point ({:.1}, {:.1})",
                point.0, point.1
            ),
        }
    }
}

/// A text element and its box.
struct TextBox {
    text: String,
    rect: Rect,
}

fn collect_texts(group: &usvg::Group, out: &mut Vec<TextBox>) {
    for node in group.children() {
        match node {
            usvg::Node::Group(g) => collect_texts(g, out),
            usvg::Node::Text(t) => {
                let b = t.abs_bounding_box();
                out.push(TextBox {
                    text: t
                        .chunks()
                        .iter()
                        .map(|c| c.text())
                        .collect::<String>()
                        .trim()
                        .to_string(),
                    rect: Rect {
                        x0: f64::from(b.left()),
                        y0: f64::from(b.top()),
                        x1: f64::from(b.right()),
                        y1: f64::from(b.bottom()),
                    },
                });
            }
            _ => {}
        }
    }
}

/// The points of a path's `d` in this crate's own dialect: absolute `M` and `L` with
/// `x y` pairs and relative `h` (dots as `M x y h0`, legend samples as `M x y h w`).
pub fn path_points(d: &str) -> Vec<Vec<(f64, f64)>> {
    let mut polylines: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut rest = d.trim();
    while let Some(cmd) = rest.chars().next() {
        rest = &rest[cmd.len_utf8()..];
        let end = rest
            .find(|c: char| c.is_ascii_alphabetic() && c != 'e')
            .unwrap_or(rest.len());
        let args: Vec<f64> = rest[..end]
            .split([' ', ','])
            .filter(|s| !s.is_empty())
            .filter_map(|s| s.parse().ok())
            .collect();
        rest = &rest[end..];
        match cmd {
            'M' | 'L' if args.len() >= 2 => {
                if cmd == 'M' || polylines.is_empty() {
                    polylines.push(Vec::new());
                }
                if let Some(line) = polylines.last_mut() {
                    line.push((args[0], args[1]));
                }
            }
            'h' if !args.is_empty() => {
                if let Some(line) = polylines.last_mut() {
                    if let Some(&(x, y)) = line.last() {
                        line.push((x + args[0], y));
                    }
                }
            }
            _ => {}
        }
    }
    polylines
}

fn rect_attr(node: roxmltree::Node<'_, '_>) -> Option<Rect> {
    let v = |name: &str| node.attribute(name).and_then(|s| s.parse::<f64>().ok());
    let (x, y, w, h) = (v("x")?, v("y")?, v("width")?, v("height")?);
    Some(Rect {
        x0: x,
        y0: y,
        x1: x + w,
        y1: y + h,
    })
}

/// Checks the three rules on the SVG document `svg`; `path` names it in errors.
///
/// # Errors
/// [`VizError::Draw`] if `svg` does not parse.
pub fn check(svg: &str, path: &Path) -> Result<Vec<Problem>> {
    let mut problems = Vec::new();

    // Text inside the viewport and apart from each other.
    let tree = crate::svg::parse(svg, path)?;
    let (w, h) = (
        f64::from(tree.size().width()),
        f64::from(tree.size().height()),
    );
    let mut texts = Vec::new();
    collect_texts(tree.root(), &mut texts);
    for t in &texts {
        let r = t.rect;
        if r.x0 < -SLACK || r.y0 < -SLACK || r.x1 > w + SLACK || r.y1 > h + SLACK {
            problems.push(Problem::TextOutside {
                text: t.text.clone(),
                bbox: (r.x0, r.y0, r.x1, r.y1),
            });
        }
    }
    for (i, a) in texts.iter().enumerate() {
        for b in &texts[i + 1..] {
            let ox = a.rect.x1.min(b.rect.x1) - a.rect.x0.max(b.rect.x0);
            let oy = a.rect.y1.min(b.rect.y1) - a.rect.y0.max(b.rect.y0);
            if ox > SLACK && oy > SLACK {
                problems.push(Problem::TextOverlap {
                    a: a.text.clone(),
                    b: b.text.clone(),
                });
            }
        }
    }

    // Legends off their own data.
    let doc = roxmltree::Document::parse(svg).map_err(|e| VizError::Draw {
        path: path.to_path_buf(),
        message: e.to_string(),
    })?;
    let groups = |class: &'static str| {
        doc.descendants()
            .filter(move |n| n.has_tag_name("g") && n.attribute("class") == Some(class))
    };
    for legend in groups("pk-legend") {
        let axes = legend.attribute("data-axes");
        let Some(frame) = legend
            .children()
            .find(|n| n.has_tag_name("rect"))
            .and_then(rect_attr)
        else {
            continue;
        };
        let plot = axes.and_then(|a| {
            let v: Vec<f64> = a.split(' ').filter_map(|s| s.parse().ok()).collect();
            (v.len() == 4).then(|| Rect {
                x0: v[0],
                y0: v[1],
                x1: v[2],
                y1: v[3],
            })
        });
        let name = legend
            .descendants()
            .find(|n| n.has_tag_name("text"))
            .and_then(|n| n.text())
            .unwrap_or("")
            .to_string();
        let covered = groups("pk-data")
            .filter(|g| g.attribute("data-axes") == axes)
            .flat_map(|g| g.children().filter(|n| n.has_tag_name("path")))
            .find_map(|p| {
                let is_line = p.attribute("stroke-linecap") != Some("square")
                    && !p.attribute("d").unwrap_or("").contains("h0");
                let half = p
                    .attribute("stroke-width")
                    .and_then(|s| s.parse::<f64>().ok())
                    .unwrap_or(1.0)
                    * 0.5;
                let r = Rect {
                    x0: frame.x0 - half,
                    y0: frame.y0 - half,
                    x1: frame.x1 + half,
                    y1: frame.y1 + half,
                };
                // Only what the clip to the plot lets through is drawn.
                let visible = |q: &(f64, f64)| plot.is_none_or(|pl| pl.contains(*q));
                path_points(p.attribute("d").unwrap_or(""))
                    .into_iter()
                    .find_map(|line| {
                        if let Some(q) =
                            line.iter().filter(|q| visible(q)).find(|q| r.contains(**q))
                        {
                            return Some(*q);
                        }
                        if is_line {
                            line.windows(2)
                                .find(|s| r.meets_segment(s[0], s[1]))
                                .map(|s| s[0])
                        } else {
                            None
                        }
                    })
            });
        if let Some(point) = covered {
            problems.push(Problem::LegendOverData {
                legend: name,
                point,
            });
        }
    }
    Ok(problems)
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;
    use crate::figure::{Panel, Series, PALETTE};

    /// An SVG of one panel drawn by the crate, with `extra` spliced before the closing tag.
    fn panel_svg(panel: &Panel, extra: &str) -> String {
        let path = Path::new("test.svg");
        let svg = crate::svg::document(path, (600, 400), |root| panel.draw(root, path).map(|_| ()))
            .unwrap();
        svg.replace("</svg>", &format!("{extra}</svg>"))
    }

    fn sample() -> Panel {
        let pts: Vec<(f64, f64)> = (0..200)
            .map(|i| (f64::from(i) * 0.05, (f64::from(i) * 0.05).sin()))
            .collect();
        Panel::new("A sine", "t (s)", "x (m)")
            .with(Series::line("sin t", pts.clone(), PALETTE[0]))
            .with(Series::line("the same, again", pts, PALETTE[1]))
    }

    #[test]
    fn a_drawn_panel_passes() {
        let problems = check(&panel_svg(&sample(), ""), Path::new("ok.svg")).unwrap();
        assert!(problems.is_empty(), "{problems:?}");
    }

    #[test]
    fn text_past_the_viewport_fails() {
        let extra = crate::svg::text(590.0, 200.0, 14.0, false, "start", "#000", "cut off");
        let problems = check(&panel_svg(&sample(), &extra), Path::new("out.svg")).unwrap();
        assert!(
            matches!(problems.as_slice(), [Problem::TextOutside { text, .. }] if text == "cut off"),
            "{problems:?}"
        );
    }

    #[test]
    fn overlapping_texts_fail() {
        let extra = crate::svg::text(300.0, 20.0, 16.0, true, "middle", "#000", "over the title");
        let problems = check(&panel_svg(&sample(), &extra), Path::new("overlap.svg")).unwrap();
        assert!(
            problems
                .iter()
                .any(|p| matches!(p, Problem::TextOverlap { a, b }
                if a == "A sine" && b == "over the title")),
            "{problems:?}"
        );
    }

    #[test]
    fn a_legend_over_its_data_fails() {
        // Move the drawn legend's box onto the middle of the plot, where the sine crosses.
        let svg = panel_svg(&sample(), "");
        let start = svg.find("<g class=\"pk-legend\"").unwrap();
        let rect = start + svg[start..].find("<rect ").unwrap();
        let end = rect + svg[rect..].find("/>").unwrap();
        let moved = format!(
            "{}<rect x=\"250\" y=\"150\" width=\"120\" height=\"60\"{}",
            &svg[..rect],
            &svg[end..]
        );
        let problems = check(&moved, Path::new("legend.svg")).unwrap();
        assert!(
            matches!(problems.as_slice(), [Problem::LegendOverData { legend, .. }] if legend == "sin t"),
            "{problems:?}"
        );
    }

    #[test]
    fn path_dialect() {
        assert_eq!(
            path_points("M1 2L3 4L5 6M7 8h0"),
            vec![
                vec![(1.0, 2.0), (3.0, 4.0), (5.0, 6.0)],
                vec![(7.0, 8.0), (7.0, 8.0)]
            ]
        );
        assert_eq!(
            path_points("M1.5 -2h26"),
            vec![vec![(1.5, -2.0), (27.5, -2.0)]]
        );
    }
}
