//! Tests of the staging folders: what a commit keeps, drops and records, and that nothing is
//! left behind by an output that was not committed or by a killed process.
use super::*;

fn temp(tag: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("mbdbench-output-{tag}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap()
}

/// The names in `dir` other than `keep`'s, sorted (to find leftovers).
fn others(dir: &Path, keep: &str) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n != keep)
        .collect();
    v.sort();
    v
}

fn commit(out: &Path, w: Writer, files: &[(&str, &str)]) {
    let mut st = Staging::begin(out, w).unwrap();
    for (rel, text) in files {
        st.write(rel, text.as_bytes()).unwrap();
    }
    st.commit().unwrap();
}

/// A rerun replaces the writer's files as a whole (a series of the old run that the new one
/// does not write is gone), keeps the user's files and the other writers', drops the report
/// made from the old summary, records everything in the manifest, and leaves no staging
/// folder beside the output.
#[test]
fn rerun_replaces_own_files_and_keeps_others() {
    let base = temp("rerun");
    let out = base.join("latest");
    commit(
        &out,
        Writer::Run,
        &[
            ("summary.json", "A"),
            ("series/c/s/x.json", "A-x"),
            ("series/c/s/y.json", "A-y"),
        ],
    );
    commit(
        &out,
        Writer::Stability,
        &[
            ("stability.json", "S"),
            ("series/long_horizon/h.json", "S-h"),
        ],
    );
    commit(
        &out,
        Writer::Report,
        &[("index.html", "R"), ("svg/c/p.svg", "R-p")],
    );
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    commit(
        &out,
        Writer::Run,
        &[("summary.json", "B"), ("series/c/s/x.json", "B-x")],
    );
    assert_eq!(read(&out.join("summary.json")), "B");
    assert_eq!(read(&out.join("series/c/s/x.json")), "B-x");
    assert!(
        !out.join("series/c/s/y.json").exists(),
        "a file of the old run survived"
    );
    assert_eq!(read(&out.join("stability.json")), "S");
    assert_eq!(read(&out.join("series/long_horizon/h.json")), "S-h");
    assert_eq!(read(&out.join("notes.txt")), "mine");
    assert!(!out.join("index.html").exists() && !out.join("svg/c/p.svg").exists());
    let m = Manifest::load(&out).unwrap().unwrap();
    let listed: Vec<&str> = m.files.keys().map(String::as_str).collect();
    assert_eq!(
        listed,
        [
            "series/c/s/x.json",
            "series/long_horizon/h.json",
            "stability.json",
            "summary.json"
        ]
    );
    assert!(m.verify("summary.json", b"B").is_ok() && m.verify("summary.json", b"A").is_err());
    assert_eq!(others(&base, "latest"), Vec::<String>::new());
    std::fs::remove_dir_all(&base).unwrap();
}

/// An output that is dropped without a commit (an error after `begin`) leaves nothing: no
/// output folder, no staging folder.
#[test]
fn uncommitted_output_leaves_nothing() {
    let base = temp("drop");
    let out = base.join("new");
    {
        let mut st = Staging::begin(&out, Writer::Run).unwrap();
        st.write("summary.json", b"x").unwrap();
    }
    assert_eq!(others(&base, ""), Vec::<String>::new());
    std::fs::remove_dir_all(&base).unwrap();
}

/// A staging folder of a process that no longer exists is removed by the next writer; a
/// user's folder that merely looks similar is not.
#[test]
fn stale_staging_is_removed() {
    let base = temp("stale");
    let out = base.join("latest");
    // No process has an id this large (pid_max is at most 2^22 on Linux).
    let stale = base.join(".latest.mbdbench-4000000000-0");
    std::fs::create_dir_all(stale.join("series")).unwrap();
    let user = base.join(".latest.mine");
    std::fs::create_dir_all(&user).unwrap();
    commit(&out, Writer::Run, &[("summary.json", "A")]);
    assert!(!stale.exists());
    assert!(user.exists());
    std::fs::remove_dir_all(&base).unwrap();
}

/// Bad output places are refused naming the path: an existing file, a bad relative path
/// inside the output, the current folder.
#[test]
fn bad_places_are_refused() {
    let base = temp("bad");
    let file = base.join("afile");
    std::fs::write(&file, "x").unwrap();
    let st = Staging::begin(&file, Writer::Run).unwrap();
    let e = st.commit().err().unwrap();
    assert!(e.contains("afile") && e.contains("not a folder"), "{e}");
    let mut st = Staging::begin(&base.join("o"), Writer::Run).unwrap();
    for rel in ["../x", "/abs", "", MANIFEST, "a/../../b"] {
        assert!(st.write(rel, b"x").is_err(), "{rel}");
    }
    drop(st);
    let e = Staging::begin(Path::new("."), Writer::Run).err().unwrap();
    assert!(e.contains("current folder"), "{e}");
    assert_eq!(others(&base, "afile"), Vec::<String>::new());
    std::fs::remove_dir_all(&base).unwrap();
}

/// A temporary file that a killed process left beside a file (`<stem>.tmp<pid>`) is removed
/// by the next atomic write of that file; a user's file of a similar name is not.
#[test]
fn stale_tmp_is_removed_by_the_next_write() {
    let base = temp("stale-tmp");
    let target = base.join("trajectory.json");
    let stale = base.join("trajectory.tmp4000000000");
    let user = base.join("trajectory.tmp-notes");
    for p in [&stale, &user] {
        std::fs::write(p, "x").unwrap();
    }
    crate::reference::write_atomic(&target, b"{}").unwrap();
    assert!(!stale.exists() && user.exists());
    assert_eq!(read(&target), "{}");
    std::fs::remove_dir_all(&base).unwrap();
}
