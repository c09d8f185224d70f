//! The gallery's `index.html`: one self-contained page (inline stylesheet, relative links) that
//! opens offline from `file://`: a contents grid of thumbnails, then each demonstration under
//! its own anchor with its physics, its figures' setup, captioned figures and a link that opens
//! the same setup in the lab. Light and dark colour schemes; nothing wider than a phone's
//! screen (figures scale down, the grid reflows).

use std::fmt::Write as _;

use crate::gallery::{Demo, GalleryFile};

/// Escapes `&`, `<`, `>` and `"` for HTML text and attributes.
pub(crate) fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            c => out.push(c),
        }
    }
    out
}

/// [`escape`], with subscript markup (`c_{pn}`, as in the figures) as `<sub>`.
pub(crate) fn rich(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(start) = rest.find("_{") {
        let Some(len) = rest[start + 2..].find('}') else {
            break;
        };
        out.push_str(&escape(&rest[..start]));
        out.push_str("<sub>");
        out.push_str(&escape(&rest[start + 2..start + 2 + len]));
        out.push_str("</sub>");
        rest = &rest[start + 2 + len + 1..];
    }
    out.push_str(&escape(rest));
    out
}

/// The stylesheet: a readable measure for text (about 70 characters), figures up to the page's
/// width on a white card (they are drawn on white, also in the dark scheme), a modular type
/// scale (1.25), and colours from custom properties switched by `prefers-color-scheme`.
const STYLE: &str = "\
:root{--fg:#1d1f21;--muted:#5b6066;--bg:#fbfbf9;--card:#ffffff;--line:#dcdcd6;--accent:#0b5fa5;\
--accent-bg:#e8f1fa;color-scheme:light dark}
@media (prefers-color-scheme:dark){:root{--fg:#e6e6e3;--muted:#a7abb0;--bg:#16181b;--card:#23262a;\
--line:#3a3e44;--accent:#7cb8f0;--accent-bg:#1f3347}}
*,*::before,*::after{box-sizing:border-box}
html{-webkit-text-size-adjust:100%}
body{margin:0;background:var(--bg);color:var(--fg);font:17px/1.6 \"DejaVu Serif\",Georgia,\"Times New Roman\",serif}
main,header{max-width:1080px;margin:0 auto;padding:0 20px}
header{padding-top:2.2rem}
h1,h2,h3,nav,figcaption,.setup,.lab,.note{font-family:\"DejaVu Sans\",Verdana,system-ui,sans-serif}
h1{font-size:2.44rem;line-height:1.15;margin:0 0 .6rem}
h2{font-size:1.56rem;line-height:1.25;margin:3rem 0 .8rem;padding-top:.4rem;border-top:1px solid var(--line)}
h2 a.anchor{color:var(--muted);text-decoration:none;font-weight:normal;margin-left:.4em;font-size:.8em}
p{max-width:70ch;margin:.8rem 0;overflow-wrap:break-word}
.lead{font-size:1.15rem}
a{color:var(--accent)}
.setup{font-size:.9rem;color:var(--muted);border-left:3px solid var(--line);padding-left:.8rem}
.lab{display:inline-block;font-size:.95rem;font-weight:bold;padding:.35rem .8rem;border-radius:6px;\
background:var(--accent-bg);text-decoration:none;margin:.2rem 0}
.note{font-size:.9rem;color:var(--muted)}
nav.contents ol{list-style:none;padding:0;margin:1.5rem 0;display:grid;gap:14px;\
grid-template-columns:repeat(auto-fill,minmax(160px,1fr))}
nav.contents a{display:block;height:100%;text-decoration:none;color:var(--fg);background:var(--card);\
border:1px solid var(--line);border-radius:8px;overflow:hidden;font-size:.85rem;line-height:1.3}
nav.contents a:hover,nav.contents a:focus{border-color:var(--accent)}
nav.contents img{display:block;width:100%;aspect-ratio:16/10;object-fit:contain;background:#fff}
nav.contents span{display:block;padding:.45rem .6rem}
figure{margin:1.4rem 0;max-width:100%}
figure img{display:block;max-width:100%;height:auto;background:#fff;border:1px solid var(--line);border-radius:6px}
figcaption{font-size:.88rem;color:var(--muted);margin-top:.45rem;max-width:70ch}
figcaption b{color:var(--fg)}
code{font-size:.9em;overflow-wrap:anywhere}
";

/// The file name of a gallery file.
fn file_name(f: &GalleryFile) -> String {
    f.path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// The page listing `demos`.
pub(crate) fn index_html(demos: &[Demo], quick: bool) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>physicskit gallery</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n<header>\n\
         <h1>physicskit gallery</h1>\n"
    );
    let _ = writeln!(
        h,
        "<p class=\"lead\">{} demonstrations of classical mechanics computed with physicskit's \
         structure-preserving integrators{}. Each figure is a vector file (SVG) in this folder; \
         the animations are GIFs.</p>",
        demos.len(),
        if quick {
            " (quick mode: fewer orbits and frames)"
        } else {
            ""
        }
    );
    // The interactive lab (web/, built beside the gallery by scripts/demo).
    h.push_str(
        "<p><a class=\"lab\" href=\"lab/index.html\">Open the interactive lab</a> Every system \
         live in the browser on the same integrators (WebAssembly): drag the bodies, switch the \
         method, watch the energy error. The lab needs a local server: run \
         <code>scripts/lab serve</code>, then open http://localhost:8000/.</p>\n</header>\n<main>\n",
    );
    h.push_str("<nav class=\"contents\" aria-label=\"Demonstrations\"><ol>\n");
    for d in demos {
        let thumb = d
            .files
            .iter()
            .find(|f| f.path.extension().is_some_and(|e| e == "svg"))
            .or_else(|| d.files.first())
            .map(file_name)
            .unwrap_or_default();
        let _ = writeln!(
            h,
            "<li><a href=\"#{slug}\"><img src=\"{thumb}\" alt=\"\" loading=\"lazy\"><span>{title}</span></a></li>",
            slug = escape(&d.slug),
            thumb = escape(&thumb),
            title = rich(&d.title)
        );
    }
    h.push_str("</ol></nav>\n");
    for d in demos {
        let slug = escape(&d.slug);
        let _ = writeln!(
            h,
            "<section id=\"{slug}\">\n<h2>{}<a class=\"anchor\" href=\"#{slug}\" aria-label=\"Link to this section\">#</a></h2>",
            rich(&d.title)
        );
        let _ = writeln!(h, "<p>{}</p>", escape(&d.explanation));
        if !d.figure.is_empty() {
            let _ = writeln!(h, "<p class=\"setup\">{}</p>", escape(&d.figure));
        }
        if let Some(link) = &d.lab {
            let _ = writeln!(
                h,
                "<p><a class=\"lab\" href=\"lab/index.html{}\">Open in the lab</a> <span class=\"note\">{}</span></p>",
                escape(&link.hash),
                escape(&link.what)
            );
        }
        for f in &d.files {
            let name = escape(&file_name(f));
            let animated = f.path.extension().is_some_and(|e| e == "gif");
            let live = if animated && d.lab.is_some() {
                " The lab runs the same motion live (link above)."
            } else {
                ""
            };
            let _ = writeln!(
                h,
                "<figure><a href=\"{name}\"><img src=\"{name}\" alt=\"{alt}\" loading=\"lazy\"></a>\
                 <figcaption><b>{kind}</b> {desc}.{live} <a href=\"{name}\">{name}</a></figcaption></figure>",
                kind = if animated { "Animation." } else { "Figure." },
                desc = rich(f.description.trim_end_matches('.')),
                alt = escape(&f.description.replace("_{", "").replace('}', ""))
            );
        }
        h.push_str("</section>\n");
    }
    h.push_str("</main>\n</body>\n</html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping() {
        assert_eq!(escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
        assert_eq!(rich("c_{pn} < 1"), "c<sub>pn</sub> &lt; 1");
    }
}
