//! The mutations of the fuzz layers: TOML value literals (extremes, wrong types, junk) and
//! text mutations of a case file (lines deleted, duplicated, swapped; keys renamed; values
//! retyped; numbers replaced; huge and nested arrays; truncation; insertions; work-limit keys).
//! No tests of its own: the parser, run-loop, binary and corpus layers apply them.
use proptest::prelude::*;
use proptest::sample::Index;

// ---------------------------------------------------------------------------------------
// Values

/// A TOML literal for `x` (`nan`, `inf`, `-inf`, or the round-trip decimal).
pub fn lit(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x:?}")
    }
}

/// Extreme numbers and wrong types, as TOML value text.
pub const EXTREMES: &[&str] = &[
    "0",
    "0.0",
    "-0.0",
    "-1",
    "-1.0",
    "1",
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "1e-308",
    "5e-324",
    "-5e-324",
    "nan",
    "-nan",
    "+nan",
    "inf",
    "-inf",
    "+inf",
    "9007199254740993",
    "9223372036854775807",
    "-9223372036854775808",
    "1e15",
    "9.0e15",
    "1e16",
    "0x7fffffff",
    "0o777",
    "0b101",
    "1_000.5",
    "\"junk\"",
    "\"\"",
    "'1.0'",
    "\"\"\"multi\nline\"\"\"",
    "true",
    "false",
    "[]",
    "[[]]",
    "[1.0]",
    "[1.0, 2.0]",
    "[0.0, nan, inf]",
    "[1.0, \"a\", true]",
    "[[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]",
    "{}",
    "{ x = 1.0 }",
    "{ order1 = [1.0] }",
    "1979-05-27T07:32:00Z",
    "07:32:00",
    "1979-05-27",
];

/// A replacement value: an extreme, any double (NaN, infinities, subnormals included), a
/// plain number, or a junk string.
pub fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        4 => prop::sample::select(EXTREMES).prop_map(str::to_string),
        3 => any::<f64>().prop_map(lit),
        2 => (-1.0e3..1.0e3f64).prop_map(lit),
        1 => (0u32..12).prop_map(|e| format!("1.0e-{e}")),
        1 => "[ -~]{0,12}".prop_map(|s| format!("{s:?}")),
        1 => "[ -~\n]{0,16}",
    ]
}

// ---------------------------------------------------------------------------------------
// Text mutations

/// A choice of one among `n` things: proptest's `Index` in the properties, a seeded `u64`
/// in the corpus (the same fixed-point scaling, so both cover the whole range).
pub trait Pick {
    /// The position chosen among `n > 0`.
    fn pick(&self, n: usize) -> usize;
    /// The element chosen in a non-empty slice.
    fn pick_in<'a, T>(&self, s: &'a [T]) -> &'a T {
        &s[self.pick(s.len())]
    }
}

impl Pick for Index {
    fn pick(&self, n: usize) -> usize {
        self.index(n)
    }
}

impl Pick for u64 {
    fn pick(&self, n: usize) -> usize {
        assert!(n > 0, "a choice among no things");
        ((n as u128 * *self as u128) >> 64) as usize
    }
}

#[derive(Debug, Clone)]
pub enum Mutation<I = Index> {
    DeleteLine(I),
    DuplicateLine(I),
    SwapLines(I, I),
    /// Replace one numeric literal.
    Number(I, String),
    /// Replace the value of one `key = value` line.
    Value(I, String),
    /// Rename the key of one `key = value` line.
    RenameKey(I, String),
    /// Cut the text at a character boundary.
    Truncate(I),
    /// Insert text at a character boundary.
    Insert(I, String),
    /// The value of one `key = value` line becomes an array of this many numbers.
    HugeArray(I, usize),
    /// The value of one `key = value` line becomes this many nested arrays.
    Nested(I, usize),
    /// A top-level key (a work limit) with this value, before the first table.
    TopKey(&'static str, String),
}

pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        2 => any::<Index>().prop_map(Mutation::DeleteLine),
        1 => any::<Index>().prop_map(Mutation::DuplicateLine),
        1 => (any::<Index>(), any::<Index>()).prop_map(|(a, b)| Mutation::SwapLines(a, b)),
        6 => (any::<Index>(), value()).prop_map(|(i, v)| Mutation::Number(i, v)),
        3 => (any::<Index>(), value()).prop_map(|(i, v)| Mutation::Value(i, v)),
        1 => (any::<Index>(), "[a-z_]{1,12}|\"[ -~]{0,8}\"|[ -~]{0,6}")
            .prop_map(|(i, k)| Mutation::RenameKey(i, k)),
        1 => any::<Index>().prop_map(Mutation::Truncate),
        2 => (any::<Index>(), "[\\[\\]{}=\",.#'\n a-z0-9]{1,8}|.{1,4}")
            .prop_map(|(i, s)| Mutation::Insert(i, s)),
        1 => (any::<Index>(), prop_oneof![0usize..8, 1000usize..20_000])
            .prop_map(|(i, n)| Mutation::HugeArray(i, n)),
        1 => (any::<Index>(), prop_oneof![1usize..8, 100usize..5_000])
            .prop_map(|(i, n)| Mutation::Nested(i, n)),
        1 => (
            prop::sample::select(&["max_steps", "max_rhs_evals"][..]),
            value()
        )
            .prop_map(|(k, v)| Mutation::TopKey(k, v)),
    ]
}

/// Byte ranges of the numeric literals of `text` (a run of `[0-9.eE+-_]` holding a digit,
/// after a space, `[`, `,` or `=`; names such as `order2_4` or `spin_d1e-2` are skipped).
pub fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let b = text.as_bytes();
    let num = |c: u8| c.is_ascii_digit() || b".eE+-_".contains(&c);
    let mut out = vec![];
    let mut i = 0;
    while i < b.len() {
        let starts = num(b[i]) && (i == 0 || b" [,=".contains(&b[i - 1]));
        if starts {
            let mut j = i;
            while j < b.len() && num(b[j]) {
                j += 1;
            }
            if b[i..j].iter().any(u8::is_ascii_digit) {
                out.push(i..j);
            }
            i = j;
        } else {
            i += 1;
        }
    }
    out
}

/// Byte ranges of the lines of `text` (with their newline).
pub fn lines(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut out = vec![];
    let mut start = 0;
    for l in text.split_inclusive('\n') {
        out.push(start..start + l.len());
        start += l.len();
    }
    out
}

/// `(key range, value range)` of every `key = value` line that is not a comment.
pub fn assignments(text: &str) -> Vec<(std::ops::Range<usize>, std::ops::Range<usize>)> {
    lines(text)
        .into_iter()
        .filter_map(|r| {
            let l = &text[r.clone()];
            let head = l.trim_start();
            if head.starts_with('#') || head.starts_with('[') {
                return None;
            }
            let eq = l.find('=')?;
            let end = r.start + l.trim_end_matches(['\n', '\r']).len();
            Some((r.start..r.start + eq, r.start + eq + 1..end))
        })
        .collect()
}

pub fn floor_char(text: &str, mut i: usize) -> usize {
    i = i.min(text.len());
    while !text.is_char_boundary(i) {
        i -= 1;
    }
    i
}

pub fn splice(text: &str, r: std::ops::Range<usize>, with: &str) -> String {
    format!("{}{with}{}", &text[..r.start], &text[r.end..])
}

/// `text` with the mutation `m` applied (unchanged when `m` finds nothing to change).
pub fn apply<I: Pick>(text: &str, m: &Mutation<I>) -> String {
    let ls = lines(text);
    let asg = assignments(text);
    match m {
        Mutation::DeleteLine(i) if !ls.is_empty() => splice(text, i.pick_in(&ls).clone(), ""),
        Mutation::DuplicateLine(i) if !ls.is_empty() => {
            let r = i.pick_in(&ls).clone();
            let l = text[r.clone()].to_string();
            splice(text, r.start..r.start, &l)
        }
        Mutation::SwapLines(a, b) if !ls.is_empty() => {
            let (mut ra, mut rb) = (a.pick_in(&ls).clone(), b.pick_in(&ls).clone());
            if ra.start > rb.start {
                std::mem::swap(&mut ra, &mut rb);
            }
            if ra == rb {
                return text.to_string();
            }
            format!(
                "{}{}{}{}{}",
                &text[..ra.start],
                &text[rb.clone()],
                &text[ra.end..rb.start],
                &text[ra.clone()],
                &text[rb.end..]
            )
        }
        Mutation::Number(i, v) => {
            let ns = numbers(text);
            if ns.is_empty() {
                return text.to_string();
            }
            splice(text, i.pick_in(&ns).clone(), v)
        }
        Mutation::Value(i, v) if !asg.is_empty() => {
            splice(text, i.pick_in(&asg).1.clone(), &format!(" {v}"))
        }
        Mutation::RenameKey(i, k) if !asg.is_empty() => {
            splice(text, i.pick_in(&asg).0.clone(), &format!("{k} "))
        }
        Mutation::Truncate(i) => text[..floor_char(text, i.pick(text.len() + 1))].to_string(),
        Mutation::Insert(i, s) => {
            let at = floor_char(text, i.pick(text.len() + 1));
            splice(text, at..at, s)
        }
        Mutation::HugeArray(i, n) if !asg.is_empty() => {
            let arr = format!("[{}]", vec!["1.0"; *n].join(", "));
            splice(text, i.pick_in(&asg).1.clone(), &format!(" {arr}"))
        }
        Mutation::Nested(i, n) if !asg.is_empty() => {
            let arr = format!("{}1.0{}", "[".repeat(*n), "]".repeat(*n));
            splice(text, i.pick_in(&asg).1.clone(), &format!(" {arr}"))
        }
        Mutation::TopKey(k, v) => {
            let line = format!("{k} = {v}\n");
            match text.find("\n[") {
                Some(p) => splice(text, p + 1..p + 1, &line),
                None => format!("{line}{text}"),
            }
        }
        _ => text.to_string(),
    }
}
