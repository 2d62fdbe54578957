//! Build script: records the git commit and the rustc version in the binary, so that
//! summaries and references name the build that produced them.
//!
//! It reruns when the commit changes (the folder of the checked-out branch's ref, `HEAD` itself
//! when detached, `packed-refs`) or when a source that makes the binary
//! changes (`src`, `cases`, `Cargo.toml`, `Cargo.lock`, `build.rs`), and never on git's
//! index: `git status` rewrites the index without any source changing, and a fresh clone
//! rebuilt the whole crate after its first `git status`. The `-dirty` mark is computed over
//! those same sources, so it is exact whenever the script reruns. A worktree's `.git` is a
//! file; the git directories come from `git rev-parse`, not from a fixed path.
use std::path::PathBuf;
use std::process::Command;

/// The sources that make the binary: their edits rerun the script and mark it dirty.
const SOURCES: [&str; 5] = ["src", "cases", "Cargo.toml", "Cargo.lock", "build.rs"];

fn git(args: &[&str]) -> Option<String> {
    Command::new("git")
        .args(args)
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
}

fn main() {
    let commit = git(&["rev-parse", "--short=12", "HEAD"]).unwrap_or_else(|| "unknown".into());
    let mut status = vec!["status", "--porcelain", "--untracked-files=no", "--"];
    status.extend(SOURCES);
    let dirty = git(&status).is_some_and(|s| !s.is_empty());
    let rustc = std::env::var("RUSTC").unwrap_or_else(|_| "rustc".into());
    let version = Command::new(rustc)
        .arg("--version")
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into());
    println!(
        "cargo:rustc-env=MBDBENCH_GIT_COMMIT={commit}{}",
        if dirty { "-dirty" } else { "" }
    );
    println!("cargo:rustc-env=MBDBENCH_RUSTC={version}");
    // HEAD names a branch and does not change on a commit; the branch's ref does (or the
    // packed refs, once packed). A worktree keeps its HEAD in its own git directory and the
    // refs in the common one.
    if let (Some(dir), Some(common)) = (
        git(&["rev-parse", "--absolute-git-dir"]),
        git(&["rev-parse", "--git-common-dir"]),
    ) {
        let (dir, common) = (PathBuf::from(dir), PathBuf::from(common));
        let common = if common.is_absolute() {
            common
        } else {
            std::env::current_dir().unwrap_or_default().join(common)
        };
        println!("cargo:rerun-if-changed={}", dir.join("HEAD").display());
        // The folder of the branch's loose ref, not the ref itself: a fresh clone keeps its
        // refs packed, and a commit then writes the loose ref, which a missing path watched
        // by name would not see.
        if let Some(r) = git(&["symbolic-ref", "-q", "HEAD"])
            && let Some(folder) = common.join(&r).parent().filter(|f| f.is_dir())
        {
            println!("cargo:rerun-if-changed={}", folder.display());
        }
        let packed = common.join("packed-refs");
        if packed.exists() {
            println!("cargo:rerun-if-changed={}", packed.display());
        }
    }
    for p in SOURCES {
        println!("cargo:rerun-if-changed={p}");
    }
}
