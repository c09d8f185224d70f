//! The catalogue's text for people, as the browser lab shows it: the same summaries, notes,
//! parameter names, units and help as the command line's, in Unicode mathematics and without
//! what only a programmer or a command-line user needs.
//!
//! The catalogue's strings are written for the command line and the Python API: they name
//! classes (`(KeplerSystem::new)`), flags (`--beta 0.7`), state columns (`p holds thetadot`)
//! and write maths in ASCII (`|p|^2/2`, `m/s^2`, `theta0`). Each becomes a second field of
//! `list --json` (`summary_text`, `note_text`, and per parameter `label`, `unit_text`,
//! `help_text`), derived here by fixed rules from the one source, so a new system's text
//! reaches the lab without a second copy:
//!
//! - a parenthesised class or constructor name is dropped (`(SineGordonChain::kink, free
//!   ends)` keeps `(free ends)`);
//! - a note's clauses (`; `-separated) about state columns or the spec are dropped, and a
//!   flag with its value (`--beta 0.7`) becomes `β = 0.7`;
//! - a note's clause with a flag that takes no number (`use --stride for long runs`) is
//!   dropped: it is an instruction for the command line;
//! - identifiers become symbols: Greek names (`theta` θ, `omega` ω, `pi` π, ...), a `dot`
//!   suffix a dot above (`thetadot0` θ̇₀), an index on one letter or an initial value's 0 a
//!   subscript (`m1` m₁, `angles0` angles₀; not `rk4`), longer snake case words spaced
//!   (`decay_rate` decay rate), `sum` Σ;
//! - `^n` and `^(..)` become superscripts where Unicode has them (`r^4` r⁴, `r^(1+eps)`
//!   r¹⁺ᵋ; on e, if not, `exp(..)`), `sqrt(` `√(`, `*` `·`, `<=` `≤` (and `>=`, `!=`),
//!   and a few names get their
//!   spelling (`Henon-Heiles` Hénon–Heiles);
//! - a few names that stay words by these rules have a symbol of their own ([`SYMBOLS`]:
//!   `omega_earth` Ω⊕, the Earth's rotation rate);
//! - in every field, the physics paragraph too: snake-case words are spaced (a method's name,
//!   `implicit_midpoint` implicit midpoint), and an index is written in one markup,
//!   `_{..}`, that the lab lowers as a subscript: a symbol of one letter (Latin or Greek, not
//!   the end of a word) with `_` and an index of up to three letters or digits, a braced
//!   group or ⊕ (`ω_c` `ω_{c}`, `V_eff` `V_{eff}`, `q_{i+1}` unchanged). The lab renders the
//!   markup and applies no rules of its own.

const GREEK: &[(&str, &str)] = &[
    ("alpha", "α"),
    ("beta", "β"),
    ("gamma", "γ"),
    ("delta", "δ"),
    ("epsilon", "ε"),
    ("eta", "η"),
    ("eps", "ε"),
    ("kappa", "κ"),
    ("lambda", "λ"),
    ("mu", "μ"),
    ("nu", "ν"),
    ("pi", "π"),
    ("rho", "ρ"),
    ("sigma", "σ"),
    ("tau", "τ"),
    ("phi", "φ"),
    ("psi", "ψ"),
    ("omega", "ω"),
    ("theta", "θ"),
];

/// Proper names the ASCII text spells without their accents or dashes.
const NAMES: &[(&str, &str)] = &[
    ("Henon-Heiles", "Hénon–Heiles"),
    ("Henon", "Hénon"),
    ("Fermi-Pasta-Ulam-Tsingou", "Fermi–Pasta–Ulam–Tsingou"),
    ("sine-Gordon", "sine–Gordon"),
    ("kink-antikink", "kink–antikink"),
];

/// Names the rules below would leave as words that have a symbol (`_{..}`: an index).
pub const SYMBOLS: &[(&str, &str)] = &[
    ("omega_earth", "Ω_{⊕}"),
    ("g_over_l", "g/l"),
    ("dq", "Δq"),
    ("dp", "Δp"),
    ("angles0", "(φ, θ, ψ)₀"),
    ("angledots0", "(φ̇, θ̇, ψ̇)₀"),
    ("quat0", "quaternion₀"),
];

/// Words of a note clause that make it a remark for programmers or command-line users.
const CODE_REMARKS: &[&str] = &["as in the spec", "p holds", "column"];

fn subscript(c: char) -> Option<char> {
    c.to_digit(10).and_then(|d| char::from_u32(0x2080 + d))
}

fn superscript(c: char) -> Option<char> {
    Some(match c {
        '0' => '⁰',
        '1' => '¹',
        '2' => '²',
        '3' => '³',
        '4' => '⁴',
        '5' => '⁵',
        '6' => '⁶',
        '7' => '⁷',
        '8' => '⁸',
        '9' => '⁹',
        '-' => '⁻',
        '+' => '⁺',
        '−' => '⁻',
        '(' => '⁽',
        ')' => '⁾',
        'ε' => 'ᵋ',
        'a' => 'ᵃ',
        'b' => 'ᵇ',
        'c' => 'ᶜ',
        'd' => 'ᵈ',
        'e' => 'ᵉ',
        'f' => 'ᶠ',
        'g' => 'ᵍ',
        'h' => 'ʰ',
        'i' => 'ⁱ',
        'j' => 'ʲ',
        'k' => 'ᵏ',
        'l' => 'ˡ',
        'm' => 'ᵐ',
        'n' => 'ⁿ',
        'o' => 'ᵒ',
        'p' => 'ᵖ',
        'r' => 'ʳ',
        's' => 'ˢ',
        't' => 'ᵗ',
        'u' => 'ᵘ',
        'v' => 'ᵛ',
        'w' => 'ʷ',
        'x' => 'ˣ',
        'y' => 'ʸ',
        'z' => 'ᶻ',
        _ => return None,
    })
}

/// `s` in subscripts, if every character has one.
fn subscripts(s: &str) -> Option<String> {
    s.chars().map(subscript).collect()
}

/// One identifier as a symbol: `theta` θ, `thetadot0` θ̇₀, `m1` m₁, `n0` n₀,
/// `p_x` p_x, `omega_c` ω_c and `c_eps` c_ε (a short or Greek index stays an index),
/// `angle_deg` angle (the unit says degrees), `decay_rate` decay rate, other words unchanged.
pub fn symbol(word: &str) -> String {
    if let Some(&(_, sym)) = SYMBOLS.iter().find(|(w, _)| *w == word) {
        return sym.to_string();
    }
    if let Some(stem) = word.strip_suffix("_deg").filter(|s| !s.is_empty()) {
        return symbol(stem);
    }
    if let Some((base, rest)) = word.split_once('_') {
        let index = rest.len() <= 2 || greek(rest).is_some();
        if !rest.contains('_') && index && !base.is_empty() {
            return format!("{}_{}", symbol(base), symbol(rest));
        }
        return word.split('_').map(symbol).collect::<Vec<_>>().join(" ");
    }
    let digits = word.len() - word.trim_end_matches(|c: char| c.is_ascii_digit()).len();
    let (stem, index) = word.split_at(word.len() - digits);
    let (stem, dotted) = match stem.strip_suffix("dot") {
        Some(s) if !s.is_empty() && (s.len() <= 2 || greek(s).is_some()) => (s, true),
        _ => (stem, false),
    };
    // An index on one letter (m1, q0) or a Greek name; an initial value's 0 on any name
    // (angles0); not the digits of a name such as rk4.
    let letter = stem.len() == 1 && stem.chars().all(|c| c.is_ascii_alphabetic());
    let initial = index.chars().all(|c| c == '0') && stem.chars().all(|c| c.is_ascii_alphabetic());
    let base = match greek(stem) {
        Some(g) => g.to_string(),
        None if digits == 0 || letter || (dotted && stem.len() <= 2) || initial => stem.to_string(),
        None => return word.to_string(),
    };
    let mut out = base;
    if dotted {
        out.push('\u{307}');
    }
    out.push_str(&subscripts(index).unwrap_or_default());
    out
}

fn greek(word: &str) -> Option<&'static str> {
    GREEK.iter().find(|(w, _)| *w == word).map(|&(_, g)| g)
}

/// Identifiers of `text` as symbols, `^n` as superscripts, `sqrt(` as `√(`, `*` as `·`.
fn maths(text: &str) -> String {
    rewrite(text, true)
}

/// Powers of `text` (prose already written for people: the gallery's physics paragraphs) as
/// superscripts, `dt^p` dtᵖ, `e^(−b r)` e⁻ᵇʳ; nothing else changes.
pub fn powers(text: &str) -> String {
    indices(&rewrite(text, false))
}

/// Snake-case words spaced and every index in the `_{..}` markup (the module's last rule).
fn indices(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let is_letter = |c: char| c.is_ascii_alphabetic() || ('\u{370}'..='\u{3ff}').contains(&c);
    let mut out = String::with_capacity(text.len() + 8);
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c == '_' && i > 0 && !out.is_empty() {
            // The word before `_`: its letters, back to the last non-letter.
            let start = chars[..i]
                .iter()
                .rposition(|&c| !is_letter(c))
                .map_or(0, |k| k + 1);
            let word_len = i - start;
            let symbol = word_len == 1 && (start == 0 || !is_letter(chars[start - 1]));
            let index_end = chars[i + 1..]
                .iter()
                .position(|&c| !(c.is_ascii_digit() || is_letter(c)))
                .map_or(chars.len(), |k| i + 1 + k);
            let next = chars.get(i + 1).copied();
            if symbol && next == Some('{') {
                if let Some(close) = chars[i + 1..].iter().position(|&c| c == '}') {
                    out.extend(&chars[i..=i + 1 + close]);
                    i += close + 2;
                    continue;
                }
            }
            if symbol && next == Some('⊕') {
                out.push_str("_{⊕}");
                i += 2;
                continue;
            }
            let index_len = index_end - (i + 1);
            if symbol && (1..=3).contains(&index_len) && chars.get(index_end) != Some(&'_') {
                out.push_str("_{");
                out.extend(&chars[i + 1..index_end]);
                out.push('}');
                i = index_end;
                continue;
            }
            // Two words of two letters or more joined by `_`: a name, spaced.
            let next_word = chars[i + 1..]
                .iter()
                .take_while(|&&c| c.is_ascii_lowercase())
                .count();
            let lower_word = word_len >= 2 && chars[start..i].iter().all(char::is_ascii_lowercase);
            if lower_word && next_word >= 2 && !continues_word(&chars, i + 1 + next_word) {
                out.push(' ');
                i += 1;
                continue;
            }
        }
        out.push(c);
        i += 1;
    }
    out
}

/// Whether a word goes on at `at` (`theta_max2` is no pair of words).
fn continues_word(chars: &[char], at: usize) -> bool {
    chars
        .get(at)
        .is_some_and(|&c| c.is_ascii_alphanumeric() || c == '_')
}

fn rewrite(text: &str, symbols: bool) -> String {
    let mut out = String::with_capacity(text.len() + 8);
    let chars: Vec<char> = text.chars().collect();
    let mut i = 0;
    while i < chars.len() {
        let c = chars[i];
        if c.is_ascii_alphabetic() && symbols {
            let start = i;
            while i < chars.len() && (chars[i].is_ascii_alphanumeric() || chars[i] == '_') {
                i += 1;
            }
            let word: String = chars[start..i].iter().collect();
            if word == "sqrt" && chars.get(i) == Some(&'(') {
                out.push('√');
            } else if word == "sum" {
                out.push('Σ');
            } else {
                out.push_str(&symbol(&word));
            }
            continue;
        }
        if c == '^' && chars.get(i + 1) == Some(&'(') {
            // r^(1+eps): the bracket's text as superscripts if each character has one.
            if let Some(close) = chars[i..].iter().position(|&c| c == ')').map(|k| i + k) {
                let inner: String = chars[i + 2..close].iter().collect();
                let inner = rewrite(&inner, symbols);
                // Spaces inside an exponent are products: dropped (e^(−b r) e⁻ᵇʳ).
                let sup = inner
                    .chars()
                    .filter(|&c| c != ' ')
                    .map(superscript)
                    .collect::<Option<String>>();
                if let Some(sup) = sup {
                    out.push_str(&sup);
                    i = close + 1;
                    continue;
                }
                // An exponent Unicode cannot raise, on e: exp(..).
                let lone_e = out.ends_with('e')
                    && !out[..out.len() - 1]
                        .chars()
                        .next_back()
                        .is_some_and(char::is_alphanumeric);
                if lone_e {
                    out.pop();
                    out.push_str("exp(");
                    out.push_str(&inner);
                    out.push(')');
                    i = close + 1;
                    continue;
                }
            }
        }
        if c == '^' {
            let start = i + 1;
            let mut j = start;
            // An exponent is one letter (dt^p) or a number.
            if chars.get(start).is_some_and(|c| c.is_ascii_alphabetic())
                && !chars
                    .get(start + 1)
                    .is_some_and(|c| c.is_ascii_alphanumeric())
            {
                if let Some(sup) = superscript(chars[start]) {
                    out.push(sup);
                    i = start + 1;
                    continue;
                }
            }
            while j < chars.len() && (chars[j].is_ascii_digit() || (j == start && chars[j] == '-'))
            {
                j += 1;
            }
            if j > start {
                out.extend(chars[start..j].iter().filter_map(|&c| superscript(c)));
                i = j;
                continue;
            }
        }
        let pair = (c, chars.get(i + 1).copied());
        // A hyphen used as a minus sign: alone between spaces (`x^2 y - y^3/3`), or before a
        // term at the start of one (`-n2`, `(-L0`), not inside a word or a number (`1e-8`).
        if c == '-' && pair.1 != Some('>') {
            let before = i.checked_sub(1).map(|k| chars[k]);
            let opens = before.is_none_or(|b| matches!(b, ' ' | '(' | '[' | ',' | '='));
            let term = pair
                .1
                .is_some_and(|n| n == ' ' || n == '(' || n.is_ascii_alphanumeric());
            if opens && term {
                out.push('−');
                i += 1;
                continue;
            }
        }
        let relation = match pair {
            ('-', Some('>')) => Some('→'),
            ('!', Some('=')) => Some('≠'),
            ('<', Some('=')) => Some('≤'),
            ('>', Some('=')) => Some('≥'),
            _ => None,
        };
        if let Some(r) = relation {
            out.push(r);
            i += 2;
            continue;
        }
        out.push(if c == '*' { '·' } else { c });
        i += 1;
    }
    out
}

/// Whether `item` (one entry of a parenthesised list) is a class or constructor name.
fn is_code_name(item: &str) -> bool {
    let item = item.trim();
    if item.contains("::") {
        return true;
    }
    if item.contains(' ') || item.is_empty() {
        return false;
    }
    let mut chars = item.chars();
    let first_upper = chars.next().is_some_and(|c| c.is_ascii_uppercase());
    let inner_upper = item.chars().skip(1).any(|c| c.is_ascii_uppercase());
    let lower = item.chars().any(|c| c.is_ascii_lowercase());
    first_upper && inner_upper && lower
}

/// `text` without parenthesised class names.
fn without_code_names(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('(') {
        let Some(close) = rest[open..].find(')').map(|c| open + c) else {
            break;
        };
        let inside = &rest[open + 1..close];
        let kept: Vec<&str> = inside
            .split(", ")
            .filter(|item| !is_code_name(item))
            .collect();
        if kept.len() == inside.split(", ").count() {
            out.push_str(&rest[..=close]);
        } else if kept.is_empty() {
            out.push_str(rest[..open].trim_end());
        } else {
            out.push_str(&rest[..open]);
            out.push('(');
            out.push_str(&kept.join(", "));
            out.push(')');
        }
        rest = &rest[close + 1..];
    }
    out.push_str(rest);
    out
}

/// `--name value` as `symbol(name) = value`, pairs joined by commas; `None` if a flag has
/// no number after it (an instruction for the command line, not a setting).
fn without_flags(text: &str) -> Option<String> {
    let words: Vec<&str> = text.split(' ').collect();
    let mut out: Vec<String> = Vec::with_capacity(words.len());
    let mut i = 0;
    let mut previous_flag = false;
    while i < words.len() {
        if let Some(name) = words[i].strip_prefix("--").filter(|n| !n.is_empty()) {
            let value = words.get(i + 1).copied().unwrap_or("");
            value.parse::<f64>().ok()?;
            if previous_flag {
                if let Some(last) = out.last_mut() {
                    last.push(',');
                }
            }
            out.push(format!("{} = {value}", symbol(name)));
            i += 2;
            previous_flag = true;
            continue;
        }
        out.push(words[i].to_string());
        previous_flag = false;
        i += 1;
    }
    Some(out.join(" "))
}

fn names(text: &str) -> String {
    let mut out = text.to_string();
    for (ascii, proper) in NAMES {
        out = out.replace(ascii, proper);
    }
    out
}

/// A summary or help line for people.
pub fn text(s: &str) -> String {
    indices(&maths(&names(&without_code_names(s))))
}

/// A note for people: [`text`] of its clauses that are not remarks for programmers, with
/// flags as settings; `None` when no clause is left.
pub fn note(s: &str) -> Option<String> {
    let kept: Vec<String> = s
        .split("; ")
        .filter(|clause| !CODE_REMARKS.iter().any(|r| clause.contains(r)))
        .filter_map(|clause| without_flags(clause).map(|c| text(&c)))
        .collect();
    (!kept.is_empty()).then(|| kept.join("; "))
}

/// A parameter's name as a symbol (`thetadot0` θ̇₀, `l1` l₁, `omega` ω).
pub fn label(name: &str) -> String {
    indices(&symbol(name))
}
