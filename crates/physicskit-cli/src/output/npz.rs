//! NPZ: a zip archive (stored, uncompressed) of NPY v1.0 arrays, as `numpy.savez` writes.
//!
//! Arrays: `t` (n,), `q` and `p` (n, ndof) or `y` (n, dim), `energy` (n,); 0-d arrays
//! `t0`, `t1`, `dt`; 0-d strings `system`, `family`, `method`; one `param_<name>` per given
//! parameter (`<f8` scalar or 1-d, `<i8` for integers, a string for choices; absent optional
//! parameters are omitted); scalar extra diagnostics as `extra_<name>`.
//!
//! The entries are listed here and written by the command line's one NPZ writer,
//! [`arrays::write_npz`](super::arrays::write_npz); `q` and `p`, strided views of the state,
//! are written without a copy.

use std::fs::File;
use std::io;

use ndarray::ArrayViewD;
use physicskit::classical::ExtraValue;

use super::arrays::{write_npz, Entry};
use super::Record;

pub(super) fn write(file: &File, record: &Record<'_>) -> io::Result<()> {
    let result = record.result;
    let f64_entry = |name: &str, shape: Vec<usize>, data| Entry::F64 {
        name: name.into(),
        shape,
        data,
    };
    let mut entries = vec![view("t", result.t.view().into_dyn())];
    let state = record.state_arrays();
    entries.extend(
        state
            .iter()
            .map(|(name, array)| view(name, array.view().into_dyn())),
    );
    if let Some(energy) = record.energy() {
        entries.push(view("energy", energy.view().into_dyn()));
    }
    let settings = record.settings();
    entries.extend(
        settings
            .iter()
            .map(|(name, value)| f64_entry(name, vec![], std::slice::from_ref(value))),
    );
    let texts = [
        ("system", record.system),
        ("family", record.family.name()),
        ("method", result.method.as_str()),
    ];
    entries.extend(texts.into_iter().map(|(name, text)| Entry::Str {
        name: name.into(),
        text,
    }));
    entries.extend(record.params.iter().filter_map(|(name, value)| {
        value.map(|value| Entry::Value {
            name: format!("param_{name}"),
            value,
        })
    }));
    entries.extend(result.extra.iter().filter_map(|(name, value)| match value {
        ExtraValue::Scalar(v) => Some(f64_entry(
            &format!("extra_{name}"),
            vec![],
            std::slice::from_ref(v),
        )),
        _ => None,
    }));
    write_npz(file, &entries)
}

fn view<'a>(name: &str, view: ArrayViewD<'a, f64>) -> Entry<'a> {
    Entry::View {
        name: name.into(),
        view,
    }
}
