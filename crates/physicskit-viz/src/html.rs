//! The gallery's `index.html`: one self-contained page (inline CSS, relative links) that opens
//! offline and shows every figure with its demonstration's physics explanation.

use std::fmt::Write as _;

use crate::gallery::Demo;

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

/// The page listing `demos`.
pub(crate) fn index_html(demos: &[Demo], quick: bool) -> String {
    let mut h = String::new();
    h.push_str(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>physicskit gallery</title>\n<style>\n\
         body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.5}\n\
         h1{margin-bottom:0.2em} h2{border-bottom:1px solid #ccc;padding-bottom:0.2em;margin-top:2em}\n\
         figure{margin:1em 0} figure img{max-width:100%;border:1px solid #ddd}\n\
         figcaption{color:#555;font-size:0.95em} nav li{margin:0.15em 0}\n\
         p.setup{color:#444;font-style:italic}\n\
         </style>\n</head>\n<body>\n<h1>physicskit gallery</h1>\n",
    );
    let _ = writeln!(
        h,
        "<p>{} demonstrations of classical mechanics computed with physicskit's \
         structure-preserving integrators{}. Every file is a plain PNG or GIF in this folder.</p>",
        demos.len(),
        if quick {
            " (quick mode: fewer orbits and frames)"
        } else {
            ""
        }
    );
    // The interactive lab (web/, built beside the gallery by scripts/demo).
    h.push_str(
        "<p><strong><a href=\"lab/index.html\">Open the interactive lab</a></strong>: every \
         system live in the browser on the same integrators (WebAssembly); drag the bodies, \
         switch the method, watch the energy error. It needs a local server: \
         <code>scripts/lab serve</code>, then http://localhost:8000/.</p>\n",
    );
    h.push_str("<nav><ol>\n");
    for d in demos {
        let _ = writeln!(
            h,
            "<li><a href=\"#{}\">{}</a></li>",
            escape(&d.slug),
            escape(&d.title)
        );
    }
    h.push_str("</ol></nav>\n");
    for d in demos {
        let _ = writeln!(
            h,
            "<section id=\"{}\">\n<h2>{}</h2>",
            escape(&d.slug),
            escape(&d.title)
        );
        let _ = writeln!(h, "<p>{}</p>", escape(&d.explanation));
        if !d.figure.is_empty() {
            let _ = writeln!(h, "<p class=\"setup\">{}</p>", escape(&d.figure));
        }
        for f in &d.files {
            let name = f
                .path
                .file_name()
                .map(|n| n.to_string_lossy().into_owned())
                .unwrap_or_default();
            let name = escape(&name);
            let _ = writeln!(
                h,
                "<figure><a href=\"{name}\"><img src=\"{name}\" alt=\"{desc}\" loading=\"lazy\"></a>\
                 <figcaption><a href=\"{name}\">{name}</a>: {desc}</figcaption></figure>",
                desc = escape(&f.description)
            );
        }
        h.push_str("</section>\n");
    }
    h.push_str("</body>\n</html>\n");
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escaping() {
        assert_eq!(escape("a<b & \"c\">"), "a&lt;b &amp; &quot;c&quot;&gt;");
    }
}
