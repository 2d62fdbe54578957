//! Everything a user needs is inside the repository: no source file, test, bench, case file,
//! document or CI script may send the reader to a file outside it (a design note, a physics
//! specification, a folder of notes beside the checkout) or to an outside tracker's issue by
//! number. The physics of the cases is in `cases/README.md`, the file formats and exit codes in
//! `docs/schemas.md`, the commands in `README.md`; papers are cited by author and year.
//!
//! The walk starts at `CARGO_MANIFEST_DIR` and reads the text files of `src/`, `tests/`,
//! `benches/`, `cases/`, `docs/`, `references/` (its scripts and notes; its JSON is data),
//! `reports/README.md`, `.ci/` and the top-level `README.md`, `Cargo.toml` and `build.rs`. A
//! failure lists every offending `file:line` with the line. The patterns are built with
//! `concat!` so that this file does not match them itself.
use std::path::{Path, PathBuf};

/// Substrings that name a file outside the repository (matched case-insensitively).
const OUTSIDE: [&str; 4] = [
    concat!("design", ".md"),
    concat!("spec/", "cases", ".md"),
    concat!("seeds", "/"),
    concat!("..", "/shared"),
];

/// The word of a tracker reference, followed by a number: `<word> 4`, `<word> #4`.
const TRACKER: &str = concat!("iss", "ue");

/// Extensions of the text files read (files of `.ci/` are read whatever their name).
const TEXT: [&str; 6] = ["rs", "md", "toml", "py", "sh", "txt"];

/// Where `line` refers outside the repository, if it does: the pattern found.
fn outside_reference(line: &str) -> Option<String> {
    let lower = line.to_ascii_lowercase();
    for p in OUTSIDE {
        if lower.contains(p) {
            return Some(p.to_string());
        }
    }
    let bytes = lower.as_bytes();
    let mut from = 0;
    while let Some(at) = lower[from..].find(TRACKER) {
        let start = from + at;
        let end = start + TRACKER.len();
        from = end;
        // A word of its own: not the tail of a longer word ("tissue").
        if start > 0 && bytes[start - 1].is_ascii_alphanumeric() {
            continue;
        }
        // Only spaces and one `#` may separate the word from its number.
        let mut k = end;
        while k < bytes.len() && bytes[k] == b' ' {
            k += 1;
        }
        if k < bytes.len() && bytes[k] == b'#' {
            k += 1;
        }
        if k > end && k < bytes.len() && bytes[k].is_ascii_digit() {
            let n: String = line[k..].chars().take_while(char::is_ascii_digit).collect();
            return Some(format!("{TRACKER} {n}"));
        }
    }
    None
}

/// The text files to check under `root`.
fn files(root: &Path) -> Vec<PathBuf> {
    let mut out = vec![];
    for top in ["README.md", "Cargo.toml", "build.rs", "reports/README.md"] {
        let p = root.join(top);
        if p.is_file() {
            out.push(p);
        }
    }
    for dir in [
        "src",
        "tests",
        "benches",
        "cases",
        "docs",
        "references",
        ".ci",
    ] {
        walk(&root.join(dir), dir == ".ci", &mut out);
    }
    out.sort();
    out
}

fn walk(dir: &Path, any_name: bool, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for e in entries.flatten() {
        let p = e.path();
        if p.is_dir() {
            walk(&p, any_name, out);
        } else if any_name
            || p.extension()
                .and_then(|x| x.to_str())
                .is_some_and(|x| TEXT.contains(&x))
        {
            out.push(p);
        }
    }
}

/// Every line of the repository's text that refers outside it, as `file:line: pattern: text`.
#[test]
fn no_reference_outside_the_repository() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = files(root);
    // The walk found the places it is meant to check (a moved root would pass vacuously).
    for must in [
        "src/lib.rs",
        "cases/README.md",
        "docs/schemas.md",
        "README.md",
    ] {
        assert!(
            files.contains(&root.join(must)),
            "{must} not among the checked files"
        );
    }
    let mut found = vec![];
    for f in &files {
        let Ok(text) = std::fs::read_to_string(f) else {
            continue; // not UTF-8 text
        };
        for (i, line) in text.lines().enumerate() {
            if let Some(p) = outside_reference(line) {
                let rel = f.strip_prefix(root).unwrap_or(f);
                found.push(format!(
                    "{}:{}: `{p}`: {}",
                    rel.display(),
                    i + 1,
                    line.trim()
                ));
            }
        }
    }
    assert!(
        found.is_empty(),
        "{} line(s) refer to something outside the repository; point them at cases/README.md, \
         docs/schemas.md or README.md, or state the rule itself:\n{}",
        found.len(),
        found.join("\n")
    );
}

/// The matcher finds each pattern and leaves ordinary words alone.
#[test]
fn matcher_finds_each_pattern() {
    let word = TRACKER;
    for hit in [
        format!("see {}", OUTSIDE[0]),
        format!("(`{}`, section 2)", OUTSIDE[1]),
        format!("in {}nine.txt", OUTSIDE[2]),
        format!("read {}/x", OUTSIDE[3]),
        format!("({word} 4)"),
        format!("{} 11, item 7", word.to_uppercase()),
        format!("({word} #10)"),
        format!("{word}#3"),
    ] {
        assert!(outside_reference(&hit).is_some(), "missed: {hit}");
    }
    for miss in [
        format!("the {word}'s bound"),
        format!("t{word} 3"),
        format!("an {word}: none"),
        "design notes".to_string(),
        "cases/README.md, section nine_spring".to_string(),
        "../references".to_string(),
    ] {
        assert!(outside_reference(&miss).is_none(), "false hit: {miss}");
    }
}
