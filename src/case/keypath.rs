//! TOML errors to key paths: a syntax error, an unknown key or a wrong type comes back from
//! the `toml` crate with a byte span, which is mapped to a dotted key path
//! (`scene[1].t_end`, `body.inertia`) by walking the spanned document tree
//! (`toml::de::DeTable`, parsed with recovery so that a syntax error still has the keys
//! before it). After a syntax error the recovered tree is trusted only for a key on the same
//! line as the error; serde's "missing field" names the table, so the field is appended.
use std::ops::Range;

use super::CaseError;

/// Maps a `toml` error to the key path at its span (found in the spanned document tree,
/// parsed with recovery so that a syntax error still has the keys before it).
pub(crate) fn toml_error(file: &str, text: &str, e: &toml::de::Error) -> CaseError {
    let mut message = e.message().trim().to_string();
    let mut key = String::new();
    if let Some(span) = e.span() {
        let (doc, syntax_errors) = toml::de::DeTable::parse_recoverable(text);
        let mut path = Vec::new();
        let last = table_path(doc.get_ref(), span.start, &mut path);
        let (line, col) = line_col(text, span.start);
        // After a syntax error the recovered tree is only trusted for a key on the same line.
        let trusted =
            syntax_errors.is_empty() || last.is_some_and(|k| line_col(text, k.start).0 == line);
        if trusted {
            key = join_path(&path);
        }
        message = format!("{message} (line {line}, column {col})");
    }
    // serde reports a missing field on its table: name the field itself.
    if let Some(field) = e
        .message()
        .strip_prefix("missing field `")
        .and_then(|s| s.split('`').next())
    {
        key = if key.is_empty() {
            field.to_string()
        } else {
            format!("{key}.{field}")
        };
    }
    CaseError {
        file: file.to_string(),
        key,
        message,
    }
}

enum Seg {
    Key(String),
    Index(usize),
}

fn join_path(path: &[Seg]) -> String {
    let mut s = String::new();
    for seg in path {
        match seg {
            Seg::Key(k) => {
                if !s.is_empty() {
                    s.push('.');
                }
                s.push_str(k);
            }
            Seg::Index(i) => s.push_str(&format!("[{i}]")),
        }
    }
    s
}

/// Appends to `path` the key (and array index) whose entry holds byte `pos`. A table opened
/// by a `[header]` has the header as its span, so containment is tested on the extent of an
/// entry: its key, its value and everything below it.
/// Returns the span of the last key pushed.
fn table_path(
    table: &toml::de::DeTable<'_>,
    pos: usize,
    path: &mut Vec<Seg>,
) -> Option<Range<usize>> {
    for (k, v) in table.iter() {
        if k.span().contains(&pos) {
            path.push(Seg::Key(k.get_ref().to_string()));
            return Some(k.span());
        }
        if extent(v).contains(&pos) {
            path.push(Seg::Key(k.get_ref().to_string()));
            return value_path(v, pos, path).or(Some(k.span()));
        }
    }
    None
}

fn value_path(
    v: &toml::Spanned<toml::de::DeValue<'_>>,
    pos: usize,
    path: &mut Vec<Seg>,
) -> Option<Range<usize>> {
    match v.get_ref() {
        toml::de::DeValue::Table(t) => table_path(t, pos, path),
        toml::de::DeValue::Array(a) => {
            let i = a.iter().position(|x| extent(x).contains(&pos))?;
            path.push(Seg::Index(i));
            value_path(&a[i], pos, path)
        }
        _ => None,
    }
}

/// The byte range covered by a value and all its descendants (with their keys).
fn extent(v: &toml::Spanned<toml::de::DeValue<'_>>) -> Range<usize> {
    let mut r = v.span();
    let mut grow = |s: Range<usize>| {
        r.start = r.start.min(s.start);
        r.end = r.end.max(s.end);
    };
    match v.get_ref() {
        toml::de::DeValue::Table(t) => {
            for (k, x) in t.iter() {
                grow(k.span());
                grow(extent(x));
            }
        }
        toml::de::DeValue::Array(a) => a.iter().for_each(|x| grow(extent(x))),
        _ => {}
    }
    r
}

/// 1-based line and column (in characters) of byte offset `pos`.
fn line_col(text: &str, pos: usize) -> (usize, usize) {
    let pos = pos.min(text.len());
    let before = text.get(..pos).unwrap_or(text);
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}
