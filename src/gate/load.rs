//! The gate's input files: `summary.json`, the `stability.json` beside it and a baseline, all
//! in the summary's schema (docs/schemas.md, "summary.json"). A file that is missing, not JSON,
//! truncated (the parser reaches its end inside a value), not in the schema or of another `schema`
//! version, or one that fails `Summary::check` (a run twice, a failed run without its failure, a
//! negative error) is unusable input: a `GateError` naming the file and what is wrong with it,
//! never a failing gate row. Each is read as a regular file of at most
//! `read_limited::SUMMARY` bytes (`crate::read_limited`): a FIFO or a link to `/dev/zero` given
//! as `--summary` or `--baseline` is refused at once, naming it.
use std::path::Path;

use super::GateError;
use crate::read_limited;
use crate::summary::Summary;

/// Reads `summary.json`; a missing, corrupt or truncated file is an error naming it.
pub fn load_summary(path: &Path) -> Result<Summary, GateError> {
    load_as(path, "summary")
}

/// `stability.json` beside `summary_path`, if that name exists (an unusable one, or one that is
/// not a regular file, is an error).
pub fn stability_beside(summary_path: &Path) -> Result<Option<Summary>, GateError> {
    let p = summary_path.with_file_name("stability.json");
    match read_limited::read(&p, read_limited::SUMMARY) {
        Err(e) if e.is_missing() => Ok(None),
        read => parse(&p, read, "stability summary").map(Some),
    }
}

/// `stability.json` beside `summary_path` when it belongs with `summary` (the same build and
/// selection, `Summary::pairs_with`); one that does not is an error naming both stamps,
/// never a study judged beside another build's run.
pub fn stability_paired(
    summary_path: &Path,
    summary: &Summary,
) -> Result<Option<Summary>, GateError> {
    let Some(st) = stability_beside(summary_path)? else {
        return Ok(None);
    };
    summary
        .pairs_with(&st)
        .map_err(|message| GateError::Unreadable {
            what: "stability summary",
            path: summary_path
                .with_file_name("stability.json")
                .display()
                .to_string(),
            message,
        })?;
    Ok(Some(st))
}

/// Reads a file in the summary's schema, checked against its folder's manifest when it has
/// one; `what` names it in errors.
pub(crate) fn load_as(path: &Path, what: &'static str) -> Result<Summary, GateError> {
    parse(path, read_limited::read(path, read_limited::SUMMARY), what)
}

/// `load_as` on the outcome of reading `path`.
fn parse(
    path: &Path,
    read: Result<Vec<u8>, read_limited::ReadError>,
    what: &'static str,
) -> Result<Summary, GateError> {
    let bad = |message: String| GateError::Unreadable {
        what,
        path: path.display().to_string(),
        message,
    };
    let bytes = read.map_err(|e| bad(e.why.to_string()))?;
    // The folder's manifest (`output`): a file changed since the suite wrote the folder may
    // sit beside another run's files.
    crate::output::verify(path, &bytes).map_err(bad)?;
    let s: Summary = serde_json::from_slice(&bytes).map_err(|e| {
        if e.is_eof() {
            bad(format!("truncated: {e}"))
        } else {
            bad(format!("not in the summary.json schema: {e}"))
        }
    })?;
    if s.schema != 1 {
        return Err(bad(format!("key `schema` is {}, expected 1", s.schema)));
    }
    s.check().map_err(bad)?;
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::super::fixture::{self, nine, passing};
    use super::*;

    /// A corrupt, truncated or missing summary is a GateError naming the file.
    #[test]
    fn corrupt_and_truncated_summary() {
        let dir = fixture::scratch("corrupt");
        let c = nine();
        let text = serde_json::to_string_pretty(&passing(&c)).unwrap();
        let good = dir.join("summary.json");
        std::fs::write(&good, &text).unwrap();
        assert_eq!(load_summary(&good).unwrap(), passing(&c));
        let cut = dir.join("truncated.json");
        std::fs::write(&cut, &text[..text.len() / 2]).unwrap();
        let bad = dir.join("corrupt.json");
        std::fs::write(&bad, text.replacen("\"records\"", "\"recrods\"", 1)).unwrap();
        let garbage = dir.join("garbage.json");
        std::fs::write(&garbage, text.replacen('{', "{]", 1)).unwrap();
        let other = dir.join("schema.json");
        std::fs::write(&other, text.replacen("\"schema\": 1", "\"schema\": 2", 1)).unwrap();
        for (p, says) in [
            (&cut, "truncated"),
            (&bad, "missing field `records`"),
            (&garbage, "not in the summary.json schema"),
            (&other, "key `schema` is 2"),
            (&dir.join("absent.json"), "cannot read"),
        ] {
            let e = load_summary(p).unwrap_err();
            let m = e.to_string();
            assert!(matches!(e, GateError::Unreadable { .. }));
            assert!(m.starts_with(&p.display().to_string()), "{m}");
            assert!(m.contains(says), "{m}");
        }
        // No stability.json beside it: none; a broken one: an error naming it.
        assert!(stability_beside(&good).unwrap().is_none());
        std::fs::write(dir.join("stability.json"), "{").unwrap();
        let e = stability_beside(&good).unwrap_err().to_string();
        assert!(
            e.contains("stability.json: unusable stability summary"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
