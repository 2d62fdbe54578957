//! The seeded mutations of the corpus layer (`corpus.rs`): a splitmix64 generator; the text
//! mutations of `mutate.rs` drawn from it with the parser layer's weights; byte mutations (junk,
//! invalid UTF-8, NUL, a byte-order mark, CRLF, a cut inside a character); and mutations of a
//! parsed JSON tree (keys dropped, renamed or swapped, types changed, extreme and negative
//! numbers, records duplicated and shuffled, wrong lengths, huge strings and arrays, deep
//! nesting, names that are paths). The same seed gives the same bytes on every machine. No
//! tests of its own.
use serde_json::{Map, Value};

use crate::mutate::{EXTREMES, Mutation, Pick, apply, lit};

/// splitmix64 (Steele, Lea and Flood 2014): 64 bits of state, a stream that depends on the
/// seed only.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in `0..n` (`n > 0`).
    pub fn below(&mut self, n: usize) -> usize {
        self.next_u64().pick(n)
    }

    /// Uniform in `lo..hi` (`lo < hi`).
    pub fn range(&mut self, lo: usize, hi: usize) -> usize {
        lo + self.below(hi - lo)
    }

    /// True with probability `percent` / 100.
    pub fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }

    pub fn choose<'a, T>(&mut self, s: &'a [T]) -> &'a T {
        &s[self.below(s.len())]
    }

    /// An index drawn with the given weights.
    pub fn weighted(&mut self, weights: &[usize]) -> usize {
        let mut x = self.below(weights.iter().sum());
        for (i, w) in weights.iter().enumerate() {
            if x < *w {
                return i;
            }
            x -= w;
        }
        unreachable!()
    }

    /// Uniform in `[lo, hi)`.
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64
    }

    /// `n` printable ASCII characters, with newlines when `newline`.
    fn ascii(&mut self, n: usize, newline: bool) -> String {
        (0..n)
            .map(|_| match self.below(if newline { 96 } else { 95 }) {
                95 => '\n',
                c => (b' ' + c as u8) as char,
            })
            .collect()
    }

    /// Any Unicode scalar value.
    fn any_char(&mut self) -> char {
        loop {
            if let Some(c) = char::from_u32(self.below(0x11_0000) as u32) {
                return c;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------
// Text and bytes

/// A replacement TOML value with the weights of `mutate::value`: an extreme, any double, a
/// plain number, a small power of ten, a junk string, junk text.
fn toml_value(r: &mut Rng) -> String {
    match r.weighted(&[4, 3, 2, 1, 1, 1]) {
        0 => r.choose(EXTREMES).to_string(),
        1 => lit(f64::from_bits(r.next_u64())),
        2 => lit(r.uniform(-1.0e3, 1.0e3)),
        3 => format!("1.0e-{}", r.below(12)),
        4 => {
            let n = r.below(13);
            format!("{:?}", r.ascii(n, false))
        }
        _ => {
            let n = r.below(17);
            r.ascii(n, true)
        }
    }
}

/// A text mutation with the weights of `mutate::mutation`.
fn text_mutation(r: &mut Rng) -> Mutation<u64> {
    let i = r.next_u64();
    match r.weighted(&[2, 1, 1, 6, 3, 1, 1, 2, 1, 1, 1, 4]) {
        0 => Mutation::DeleteLine(i),
        1 => Mutation::DuplicateLine(i),
        2 => Mutation::SwapLines(i, r.next_u64()),
        3 => Mutation::Number(i, toml_value(r)),
        4 => Mutation::Value(i, toml_value(r)),
        5 => {
            let key = match r.below(3) {
                0 => (0..r.range(1, 13))
                    .map(|_| *r.choose(b"abcdefghijklmnopqrstuvwxyz_") as char)
                    .collect(),
                1 => {
                    let n = r.below(9);
                    format!("\"{}\"", r.ascii(n, false).replace(['"', '\\'], "x"))
                }
                _ => {
                    let n = r.below(7);
                    r.ascii(n, false)
                }
            };
            Mutation::RenameKey(i, key)
        }
        6 => Mutation::Truncate(i),
        7 => {
            let s = if r.chance(50) {
                (0..r.range(1, 9))
                    .map(|_| *r.choose(b"[]{}=\",.#'\n abcxyz0189") as char)
                    .collect()
            } else {
                (0..r.range(1, 5)).map(|_| r.any_char()).collect()
            };
            Mutation::Insert(i, s)
        }
        8 => {
            let n = if r.chance(50) {
                r.below(8)
            } else {
                r.range(1000, 20_000)
            };
            Mutation::HugeArray(i, n)
        }
        9 => {
            let n = if r.chance(50) {
                r.range(1, 8)
            } else {
                r.range(100, 5_000)
            };
            Mutation::Nested(i, n)
        }
        10 => {
            let key = *r.choose(&["max_steps", "max_rhs_evals", "max_adaptive_rhs_evals"]);
            Mutation::TopKey(key, toml_value(r))
        }
        // Beyond the parser layer's mix: a number that passes validation more often, so
        // that more mutated cases load and reach planning and the run.
        _ => Mutation::Number(i, plausible(r)),
    }
}

/// An ordinary number of either sign over eight decades, or a small integer.
fn plausible(r: &mut Rng) -> String {
    if r.chance(25) {
        return r.below(10).to_string();
    }
    let x = 10f64.powf(r.uniform(-4.0, 4.0));
    lit(if r.chance(20) { -x } else { x })
}

/// Byte sequences that are not UTF-8: stray bytes, an overlong NUL, a surrogate, a code
/// point past U+10FFFF, a cut three-byte sequence.
const INVALID_UTF8: &[&[u8]] = &[
    &[0xff],
    &[0xfe, 0xff],
    &[0xc0, 0x80],
    &[0xed, 0xa0, 0x80],
    &[0x80],
    &[0xf4, 0x90, 0x80, 0x80],
    &[0xe2, 0x82],
];

/// One byte-level mutation of `b`.
fn byte_mutation(r: &mut Rng, b: &mut Vec<u8>) {
    let at = r.below(b.len() + 1);
    match r.below(8) {
        0 => {
            let junk: Vec<u8> = (0..r.range(1, 17)).map(|_| r.next_u64() as u8).collect();
            b.splice(at..at, junk);
        }
        1 => {
            let bad = r.choose(INVALID_UTF8);
            b.splice(at..at, bad.iter().copied());
        }
        2 => b.insert(at, 0),
        3 => {
            b.splice(0..0, [0xef, 0xbb, 0xbf]);
        }
        4 => {
            let to: &[u8] = if r.chance(50) { b"\r\n" } else { b"\r" };
            let mut out = Vec::with_capacity(b.len() * 2);
            for &c in b.iter() {
                if c == b'\n' {
                    out.extend_from_slice(to);
                } else {
                    out.push(c);
                }
            }
            *b = out;
        }
        5 if !b.is_empty() => {
            let i = r.below(b.len());
            b[i] = r.next_u64() as u8;
        }
        6 => b.truncate(at),
        _ if !b.is_empty() => {
            let from = r.below(b.len());
            let to = (from + r.range(1, 4096)).min(b.len());
            let chunk = b[from..to].to_vec();
            b.splice(at..at, chunk);
        }
        _ => b.push(b'\n'),
    }
}

/// A mutated case file: one to four text mutations, then now and then a byte mutation.
pub fn mutate_toml(r: &mut Rng, text: &str) -> (Vec<u8>, String) {
    let mut t = text.to_string();
    let n = count(r, 4);
    for _ in 0..n {
        t = apply(&t, &text_mutation(r));
    }
    let mut b = t.into_bytes();
    let bytes = r.chance(20);
    if bytes {
        byte_mutation(r, &mut b);
    }
    let what = format!("{n} text mutations{}", if bytes { " + bytes" } else { "" });
    (b, what)
}

/// How many mutations: one half the time, two a quarter, else up to `most`.
fn count(r: &mut Rng, most: usize) -> usize {
    match r.below(4) {
        0 | 1 => 1,
        2 => 2,
        _ => r.range(1, most + 1),
    }
}

/// A mutated JSON file: mostly one to three mutations of its parsed tree (written pretty or
/// compact), otherwise text mutations of its lines and numbers; now and then a byte mutation.
pub fn mutate_json(r: &mut Rng, text: &str) -> (Vec<u8>, String) {
    let (mut b, what, p_bytes) = if r.chance(80) {
        let mut v: Value = serde_json::from_str(text).expect("a base input is valid JSON");
        let mut tokens = vec![];
        let n = count(r, 3);
        let ops: Vec<&str> = (0..n)
            .map(|_| tree_mutation(r, &mut v, &mut tokens))
            .collect();
        let pretty = r.chance(50);
        let t = render(&v, pretty, &tokens);
        (t.into_bytes(), format!("tree {}", ops.join(", ")), 15)
    } else {
        let mut t = text.to_string();
        let n = count(r, 3);
        for _ in 0..n {
            t = apply(&t, &text_mutation(r));
        }
        (t.into_bytes(), format!("{n} text mutations"), 40)
    };
    let bytes = r.chance(p_bytes);
    if bytes {
        byte_mutation(r, &mut b);
    }
    (b, format!("{what}{}", if bytes { " + bytes" } else { "" }))
}

// ---------------------------------------------------------------------------------------
// JSON trees

/// Number literals that a JSON tree cannot hold (out of range, NaN, infinities, leading
/// zeros) or that sit at the edges of the doubles and of the integers; and deep nesting.
const JSON_EXTREMES: &[&str] = &[
    "1e308",
    "-1e308",
    "1.7976931348623157e308",
    "5e-324",
    "-5e-324",
    "2.2250738585072014e-308",
    "-0.0",
    "-0",
    "0",
    "-1",
    "1e-320",
    "9007199254740993",
    "18446744073709551615",
    "18446744073709551616",
    "-9223372036854775809",
    "123456789012345678901234567890.5",
    "1e999",
    "-1e999",
    "1e400",
    "NaN",
    "Infinity",
    "-Infinity",
    "nan",
    "inf",
    "01",
    ".5",
    "+1",
    "1E+2",
];

/// Plausible values of the wrong field: names of cases, scenes and variants, statuses, paths,
/// markup, control and non-ASCII characters, small numbers, and the other types.
fn vocabulary(r: &mut Rng) -> Value {
    const WORDS: &[&str] = &[
        "",
        "nine_spring",
        "two_angles",
        "large",
        "gimbal_lock",
        "spin_d0",
        "heavy_top",
        "so3",
        "quat",
        "rk4",
        "dopri5",
        "gauss6",
        "body",
        "spatial",
        "ok",
        "failed",
        "n/a",
        "work_limit",
        "rotation_error_max",
        "energy_drift_max",
        "largest_stable_dt",
        ".",
        "..",
        "/",
        "/dev/null",
        "../escape",
        "../../escape",
        "series/../../escape.json",
        "a/b/c",
        "<script>alert(1)</script>",
        "a\u{0}b",
        "\u{202e}rtl",
        "漢字🙂",
        "%s%n",
        "\n\r\t",
    ];
    match r.below(14) {
        0..=7 => Value::from(*r.choose(WORDS)),
        8 => Value::from("x".repeat(r.range(200, 400))),
        9 => Value::from(*r.choose(&[0.0, 1.0, -1.0, 0.5, 1e-3, 2.0, 3.0, 1e-12])),
        10 => Value::from(r.below(5) as u64),
        11 => Value::Null,
        12 => Value::Bool(r.chance(50)),
        _ => {
            if r.chance(50) {
                Value::Array(vec![])
            } else {
                Value::Object(Map::new())
            }
        }
    }
}

#[derive(Clone, Debug)]
enum Seg {
    Key(String),
    At(usize),
}

/// The paths of every node under `v` (the root is the empty path).
fn paths(v: &Value, at: &mut Vec<Seg>, out: &mut Vec<Vec<Seg>>) {
    out.push(at.clone());
    match v {
        Value::Object(m) => {
            for (k, x) in m {
                at.push(Seg::Key(k.clone()));
                paths(x, at, out);
                at.pop();
            }
        }
        Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                at.push(Seg::At(i));
                paths(x, at, out);
                at.pop();
            }
        }
        _ => {}
    }
}

fn node<'a>(v: &'a mut Value, p: &[Seg]) -> &'a mut Value {
    p.iter().fold(v, |v, s| match s {
        Seg::Key(k) => &mut v[k.as_str()],
        Seg::At(i) => &mut v[*i],
    })
}

/// A random node for which `ok` holds (the root when none does).
fn pick_node(r: &mut Rng, v: &Value, ok: impl Fn(&Value, &[Seg]) -> bool) -> Vec<Seg> {
    let mut all = vec![];
    paths(v, &mut vec![], &mut all);
    let fit: Vec<Vec<Seg>> = all.into_iter().filter(|p| ok(lookup(v, p), p)).collect();
    if fit.is_empty() {
        vec![]
    } else {
        r.choose(&fit).clone()
    }
}

fn lookup<'a>(v: &'a Value, p: &[Seg]) -> &'a Value {
    p.iter().fold(v, |v, s| match s {
        Seg::Key(k) => &v[k.as_str()],
        Seg::At(i) => &v[*i],
    })
}

/// A placeholder string that `render` replaces by the raw literal `tokens[i]`.
fn token(tokens: &mut Vec<String>, literal: String) -> Value {
    tokens.push(literal);
    Value::from(format!("@@mbdbench-fuzz-{}@@", tokens.len() - 1))
}

/// `v` as JSON text with its placeholders replaced by their raw literals.
fn render(v: &Value, pretty: bool, tokens: &[String]) -> String {
    let mut t = if pretty {
        serde_json::to_string_pretty(v)
    } else {
        serde_json::to_string(v)
    }
    .unwrap();
    for (i, lit) in tokens.iter().enumerate().rev() {
        t = t.replace(&format!("\"@@mbdbench-fuzz-{i}@@\""), lit);
    }
    t
}

/// A field of an object (rather than an element of an array): where a type change or a
/// wrong value matters most.
fn member(p: &[Seg]) -> bool {
    matches!(p.last(), Some(Seg::Key(_)))
}

/// Applies one mutation to the tree `v`; returns its name.
fn tree_mutation(r: &mut Rng, v: &mut Value, tokens: &mut Vec<String>) -> &'static str {
    let w = [3, 1, 1, 3, 4, 2, 2, 2, 1, 3, 1, 1, 1, 1, 5];
    match r.weighted(&w) {
        0 => {
            let p = pick_node(r, v, |x, _| x.as_object().is_some_and(|m| !m.is_empty()));
            if let Value::Object(m) = node(v, &p) {
                let k = r.choose(&m.keys().cloned().collect::<Vec<_>>()).clone();
                m.remove(&k);
            }
            "drop key"
        }
        1 => {
            let p = pick_node(r, v, |x, _| x.as_object().is_some_and(|m| !m.is_empty()));
            if let Value::Object(m) = node(v, &p) {
                let keys: Vec<String> = m.keys().cloned().collect();
                let k = r.choose(&keys).clone();
                let to = match r.below(4) {
                    0 => format!("{k}_"),
                    1 => k.to_uppercase(),
                    2 => String::new(),
                    _ => r.choose(&keys).clone(),
                };
                if let Some(x) = m.remove(&k) {
                    m.insert(to, x);
                }
            }
            "rename key"
        }
        2 => {
            let p = pick_node(r, v, |x, _| x.as_object().is_some_and(|m| m.len() >= 2));
            if let Value::Object(m) = node(v, &p) {
                let keys: Vec<String> = m.keys().cloned().collect();
                let (a, b) = (r.choose(&keys).clone(), r.choose(&keys).clone());
                let x = m[&a].clone();
                m[&a] = std::mem::replace(&mut m[&b], x);
            }
            "swap fields"
        }
        3 => {
            let any = r.chance(50);
            let p = pick_node(r, v, |_, p| !p.is_empty() && (any || member(p)));
            *node(v, &p) = vocabulary(r);
            "retype"
        }
        4 => {
            let p = pick_node(r, v, |x, p| x.is_number() && !p.is_empty());
            let lit = r.choose(JSON_EXTREMES).to_string();
            *node(v, &p) = token(tokens, lit);
            "extreme number"
        }
        5 => {
            let p = pick_node(r, v, |x, p| x.is_number() && !p.is_empty());
            let x = node(v, &p);
            let lit = match x.as_i64() {
                Some(n) => format!("{}", -(n as i128)),
                None => format!("{:e}", -x.as_f64().unwrap_or(1.0)),
            };
            *x = token(tokens, lit);
            "negate"
        }
        6 => {
            let p = pick_node(r, v, |_, p| member(p));
            *node(v, &p) = vocabulary(r);
            "wrong value"
        }
        7 => {
            let p = pick_node(r, v, |x, _| x.as_array().is_some_and(|a| !a.is_empty()));
            if let Value::Array(a) = node(v, &p) {
                let x = r.choose(a).clone();
                let at = r.below(a.len() + 1);
                a.insert(at, x);
            }
            "duplicate element"
        }
        8 => {
            let p = pick_node(r, v, |x, _| x.as_array().is_some_and(|a| a.len() >= 2));
            if let Value::Array(a) = node(v, &p) {
                for i in (1..a.len()).rev() {
                    let j = r.below(i + 1);
                    a.swap(i, j);
                }
            }
            "shuffle"
        }
        9 => {
            let p = pick_node(r, v, |x, _| x.is_array());
            if let Value::Array(a) = node(v, &p) {
                if a.is_empty() || r.chance(40) {
                    let x = a.last().cloned().unwrap_or(Value::from(1.0));
                    for _ in 0..r.range(1, 6) {
                        a.push(x.clone());
                    }
                } else if r.chance(50) {
                    a.pop();
                } else {
                    let n = r.below(a.len());
                    a.truncate(n);
                }
            }
            "wrong length"
        }
        10 => {
            let p = pick_node(r, v, |x, p| x.is_string() || member(p));
            let unit = *r.choose(&["x", "é", "../", "<b>", "\u{0}", "\\", "\""]);
            *node(v, &p) = Value::from(unit.repeat(r.range(10_000, 1_000_000)));
            "huge string"
        }
        11 => {
            let p = pick_node(r, v, |x, _| x.as_array().is_some_and(|a| !a.is_empty()));
            if let Value::Array(a) = node(v, &p) {
                let x = a[0].clone();
                // At most about 8 MB of text.
                let size = serde_json::to_string(&x).map_or(8, |s| s.len() + 2);
                let n = r.range(10_000, 200_000).min(8_000_000 / size);
                a.resize(a.len() + n, x);
            }
            "huge array"
        }
        12 => {
            let p = pick_node(r, v, |_, p| !p.is_empty());
            let n = if r.chance(50) {
                r.range(1, 8)
            } else {
                r.range(100, 5_000)
            };
            let lit = format!("{}1.0{}", "[".repeat(n), "]".repeat(n));
            *node(v, &p) = token(tokens, lit);
            "nesting"
        }
        13 => {
            let from = pick_node(r, v, |_, _| true);
            let x = lookup(v, &from).clone();
            let p = pick_node(r, v, |_, p| !p.is_empty());
            *node(v, &p) = x;
            "copy subtree"
        }
        _ => {
            let p = pick_node(r, v, |x, p| x.is_number() && !p.is_empty());
            let x = node(v, &p);
            let f = *r.choose(&[0.0, 0.5, 2.0, 10.0, 1e-3, 1e3, 1.0 + 1e-9, 1.0 - 1e-15]);
            let y = x.as_f64().unwrap_or(1.0) * f;
            // An integer stays an integer (a count scaled, not retyped).
            let lit = if x.is_u64() || x.is_i64() {
                format!("{}", y.round() as i64)
            } else {
                format!("{y:e}")
            };
            *x = token(tokens, lit);
            "scale number"
        }
    }
}
