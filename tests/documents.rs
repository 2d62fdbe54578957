//! The documents say what the code does: every contents list names its page's sections in
//! order, every command and flag the binary's `--help` lists is in README.md's "Commands"
//! block and every one there exists, every case file is named in README.md and
//! cases/README.md, every link to a local file or anchor resolves (anchors by GitHub's slug
//! rule), the `advise --json` schema pointer is the same in README.md and `advise --help`, and
//! README.md's pull-request recipe is the commands `.ci/run` runs, in its order.
//! Cheap checks only: each reads the files and the binary's help, nothing runs.
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;

fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(repo().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

/// The binary's help for `args` (`[]`: the top level), its standard output.
fn help(args: &[&str]) -> String {
    let o = Command::new(env!("CARGO_BIN_EXE_mbdbench"))
        .args(args)
        .arg("--help")
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(0), "mbdbench {args:?} --help");
    String::from_utf8(o.stdout).unwrap()
}

/// The lines of a Markdown text outside fenced code blocks, with their line numbers (1-based).
fn prose(md: &str) -> Vec<(usize, &str)> {
    let mut fenced = false;
    let mut out = vec![];
    for (i, line) in md.lines().enumerate() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
        } else if !fenced {
            out.push((i + 1, line));
        }
    }
    out
}

/// The headings (level, rendered text: code-span backticks dropped) outside code blocks.
fn headings(md: &str) -> Vec<(usize, String)> {
    prose(md)
        .into_iter()
        .filter_map(|(_, l)| {
            let level = l.chars().take_while(|&c| c == '#').count();
            let rest = l[level..].strip_prefix(' ')?;
            (level > 0).then(|| {
                (
                    level,
                    rest.trim().trim_end_matches('#').trim().replace('`', ""),
                )
            })
        })
        .collect()
}

/// GitHub's anchor for a heading's text: lower case, every character that is not a letter,
/// digit, `_`, `-` or space dropped, each space a `-` (so "`advise --json`" is `advise---json`).
fn slug(text: &str) -> String {
    text.to_lowercase()
        .chars()
        .filter(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | ' '))
        .map(|c| if c == ' ' { '-' } else { c })
        .collect()
}

/// Every anchor of a page: its headings' slugs, a repeated one suffixed `-1`, `-2`, ... as
/// GitHub does.
fn anchors(md: &str) -> BTreeSet<String> {
    let mut seen: BTreeMap<String, usize> = BTreeMap::new();
    let mut out = BTreeSet::new();
    for (_, h) in headings(md) {
        let s = slug(&h);
        let n = seen.entry(s.clone()).or_insert(0);
        out.insert(if *n == 0 {
            s.clone()
        } else {
            format!("{s}-{n}")
        });
        *n += 1;
    }
    out
}

/// A paragraph with its code spans blanked out (a `](` inside one is no link), or as it is
/// when its backticks do not pair.
fn without_code_spans(paragraph: &str) -> String {
    if paragraph.matches('`').count() % 2 == 1 {
        return paragraph.to_string();
    }
    let mut inside = false;
    paragraph
        .chars()
        .map(|c| {
            if c == '`' {
                inside = !inside;
                ' '
            } else if inside {
                ' '
            } else {
                c
            }
        })
        .collect()
}

/// The targets of the inline links `[text](target)` of a page, outside code.
fn link_targets(md: &str) -> Vec<String> {
    let text: Vec<&str> = prose(md).into_iter().map(|(_, l)| l).collect();
    let mut out = vec![];
    for paragraph in text.join("\n").split("\n\n") {
        let p = without_code_spans(paragraph);
        let mut rest = p.as_str();
        while let Some(i) = rest.find("](") {
            rest = &rest[i + 2..];
            let Some(end) = rest.find(')') else { break };
            let target = &rest[..end];
            if !target.is_empty() && !target.contains(char::is_whitespace) {
                out.push(target.to_string());
            }
        }
    }
    out
}

/// The section of a page under the heading `heading` (to the next heading of its level or
/// above).
fn section<'a>(md: &'a str, heading: &str) -> &'a str {
    let start = md
        .find(&format!("\n{heading}\n"))
        .unwrap_or_else(|| panic!("no heading `{heading}`"))
        + 1;
    let level = heading.chars().take_while(|&c| c == '#').count();
    let body = &md[start + heading.len()..];
    let mut fenced = false;
    let mut offset = 0;
    for line in body.split_inclusive('\n') {
        if line.starts_with("```") {
            fenced = !fenced;
        }
        let l = line.chars().take_while(|&c| c == '#').count();
        if !fenced && l > 0 && l <= level && line[l..].starts_with(' ') {
            break;
        }
        offset += line.len();
    }
    &md[start..start + heading.len() + offset]
}

/// The numbered contents list of a page (the lines after `Contents:`) as the anchors its
/// items link to first; None when the page has none.
fn contents(md: &str) -> Option<Vec<String>> {
    let start = md.find("\nContents:\n")? + "\nContents:\n".len();
    let mut items = vec![];
    for line in md[start..].lines().skip_while(|l| l.is_empty()) {
        if line.is_empty() {
            break;
        }
        let item = line
            .split_once(". ")
            .filter(|(n, _)| n.parse::<u32>().is_ok());
        if let Some((_, rest)) = item {
            let anchor = rest
                .split_once("](#")
                .and_then(|(_, a)| a.split_once(')'))
                .map(|(a, _)| a.to_string())
                .unwrap_or_else(|| panic!("a contents item without an anchor: {line}"));
            items.push(anchor);
        }
    }
    Some(items)
}

/// The long flags (`--name`) a text names, in order of appearance.
fn flags(text: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut rest = text;
    while let Some(i) = rest.find("--") {
        rest = &rest[i + 2..];
        let name: String = rest
            .chars()
            .take_while(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || *c == '-')
            .collect();
        if !name.is_empty() && name.chars().next().unwrap().is_ascii_lowercase() {
            out.insert(format!("--{name}"));
        }
    }
    out
}

/// The flags of a `--help` text's `Options:` list, without `--help` and `--version`.
fn help_flags(help: &str) -> BTreeSet<String> {
    let options = help
        .split_once("Options:\n")
        .unwrap_or_else(|| panic!("no Options in {help}"))
        .1;
    options
        .lines()
        .take_while(|l| !l.is_empty())
        .filter_map(|l| {
            let l = l.trim_start();
            // `-h, --help`: the long form after the short one.
            let l = match l.split_once(", ") {
                Some((short, long)) if short.len() == 2 && !short.starts_with("--") => long,
                _ => l,
            };
            let flag = l.split([' ', '=']).next()?;
            flag.starts_with("--").then(|| flag.to_string())
        })
        .filter(|f| f != "--help" && f != "--version")
        .collect()
}

/// The subcommands the top-level help lists, without `help`.
fn help_commands(top: &str) -> BTreeSet<String> {
    let list = top.split_once("Commands:\n").expect("no Commands").1;
    list.lines()
        .take_while(|l| !l.is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .filter(|c| *c != "help")
        .map(str::to_string)
        .collect()
}

/// README.md's "Commands" block: per command (`""`: the main job, `mbdbench` alone), the
/// flags its line names.
fn readme_commands(readme: &str) -> BTreeMap<String, BTreeSet<String>> {
    let commands = section(readme, "## Commands");
    let block = commands
        .split_once("```sh\n")
        .and_then(|(_, b)| b.split_once("```"))
        .expect("no ```sh block in README's Commands")
        .0;
    let mut out = BTreeMap::new();
    for line in block.lines().filter(|l| !l.trim().is_empty()) {
        let line = line.split(" #").next().unwrap();
        let mut words = line.split_whitespace();
        assert_eq!(words.next(), Some("mbdbench"), "README Commands: {line}");
        let command = words
            .next()
            .filter(|w| !w.starts_with('[') && !w.starts_with('-'))
            .unwrap_or("");
        let previous = out.insert(command.to_string(), flags(line));
        assert!(
            previous.is_none(),
            "README Commands lists `{command}` twice"
        );
    }
    out
}

/// The Markdown pages whose links must resolve.
fn pages() -> Vec<String> {
    let mut pages: Vec<String> = ["README.md", "cases/README.md", "reports/README.md"]
        .map(String::from)
        .to_vec();
    for f in std::fs::read_dir(repo().join("docs")).unwrap() {
        let f = f.unwrap().path();
        if f.extension().is_some_and(|e| e == "md") {
            pages.push(format!("docs/{}", f.file_name().unwrap().to_str().unwrap()));
        }
    }
    pages
}

#[test]
fn contents_lists_name_every_section_in_order() {
    let mut checked = 0;
    for page in pages() {
        let md = read(&page);
        let Some(items) = contents(&md) else { continue };
        let sections: Vec<String> = headings(&md)
            .into_iter()
            .filter(|(level, _)| *level == 2)
            .map(|(_, h)| slug(&h))
            .collect();
        assert_eq!(
            items, sections,
            "{page}: the contents list (left) and the page's `##` sections (right) differ"
        );
        checked += 1;
    }
    assert!(
        checked >= 3,
        "README.md, cases/README.md and docs/schemas.md have contents"
    );
}

#[test]
fn readme_commands_are_the_binarys() {
    let readme = read("README.md");
    let documented = readme_commands(&readme);
    let top = help(&[]);
    let mut commands = help_commands(&top);
    commands.insert(String::new());
    let listed: BTreeSet<String> = documented.keys().cloned().collect();
    assert_eq!(
        listed, commands,
        "README's Commands block (left) and `mbdbench --help` (right; \"\": the main job)"
    );
    // Every command takes these two, said once below the block.
    let global = ["--cases", "--references"];
    let commands_text = section(&readme, "## Commands");
    for g in global {
        assert!(
            commands_text.contains(&format!("`{g} DIR`")),
            "README's Commands does not say every command takes `{g} DIR`"
        );
    }
    for (command, in_readme) in &documented {
        let args: Vec<&str> = [command.as_str()]
            .into_iter()
            .filter(|c| !c.is_empty())
            .collect();
        let mut in_help = help_flags(&help(&args));
        in_help.retain(|f| !global.contains(&f.as_str()));
        assert_eq!(
            in_readme, &in_help,
            "`mbdbench {command}`: README's Commands line (left) and its --help (right)"
        );
    }
}

#[test]
fn every_case_file_is_named_in_both_readmes() {
    let readme = read("README.md");
    let catalogue = read("cases/README.md");
    let mut n = 0;
    for f in std::fs::read_dir(repo().join("cases")).unwrap() {
        let f = f.unwrap().path();
        if f.extension().is_none_or(|e| e != "toml") {
            continue;
        }
        let name = format!("`{}`", f.file_stem().unwrap().to_str().unwrap());
        assert!(
            readme.contains(&name),
            "README.md does not name the case {name}"
        );
        assert!(
            catalogue.contains(&name),
            "cases/README.md does not name the case {name}"
        );
        n += 1;
    }
    assert!(n > 0, "no case files in cases/");
}

/// The page (`None`: not Markdown) a link from `page` to `target` points at, after checking
/// the file exists.
fn resolve(page: &str, target: &str) -> (PathBuf, Option<String>) {
    let (path, anchor) = match target.split_once('#') {
        Some((p, a)) => (p, Some(a.to_string())),
        None => (target, None),
    };
    let from = Path::new(page).parent().unwrap();
    let file = if path.is_empty() {
        PathBuf::from(page)
    } else {
        from.join(path)
    };
    assert!(
        repo().join(&file).exists(),
        "{page}: the link `{target}` points at {}, which does not exist",
        file.display()
    );
    (file, anchor)
}

#[test]
fn every_local_link_and_anchor_resolves() {
    let mut checked = 0;
    for page in pages() {
        for target in link_targets(&read(&page)) {
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            let (file, anchor) = resolve(&page, &target);
            let Some(anchor) = anchor else { continue };
            assert!(
                file.extension().is_some_and(|e| e == "md"),
                "{page}: the link `{target}` has an anchor into a file that is not Markdown"
            );
            let md = std::fs::read_to_string(repo().join(&file)).unwrap();
            assert!(
                anchors(&md).contains(&anchor),
                "{page}: the link `{target}`: {} has no heading whose anchor is #{anchor}",
                file.display()
            );
            checked += 1;
        }
    }
    assert!(
        checked > 10,
        "only {checked} anchored links found: the parser is broken"
    );
}

#[test]
fn advise_json_schema_pointer_agrees() {
    let advise = help(&["advise"]);
    let line = advise
        .lines()
        .find(|l| l.trim_start().starts_with("--json"))
        .expect("advise --help lists --json");
    let pointer = line
        .split_once("(schema: ")
        .and_then(|(_, p)| p.split_once(')'))
        .unwrap_or_else(|| panic!("advise --help names no schema: {line}"))
        .0;
    let (file, heading) = pointer
        .split_once(", ")
        .unwrap_or_else(|| panic!("advise --help's schema names no section: {pointer}"));
    let heading = heading.trim_matches('"');
    let schemas = read(file);
    assert!(
        headings(&schemas).iter().any(|(_, h)| h == heading),
        "advise --help points at {file}, \"{heading}\", which has no such heading"
    );
    let readme = read("README.md");
    let sentence = "`--json` follows the schema in [";
    let after = section(&readme, "## Commands")
        .split_once(sentence)
        .unwrap_or_else(|| panic!("README's Commands lacks \"{sentence}\""))
        .1;
    let target = after
        .split_once("](")
        .and_then(|(_, t)| t.split_once(')'))
        .unwrap()
        .0;
    assert_eq!(
        target,
        format!("{file}#{}", slug(heading)),
        "README's advise --json schema link and advise --help's pointer differ"
    );
}

#[test]
fn the_pull_request_recipe_is_what_ci_runs() {
    let readme = read("README.md");
    let intro = "the commands `.ci/run` runs, in order";
    let block = readme
        .split_once(intro)
        .and_then(|(_, r)| r.split_once("```sh\n"))
        .and_then(|(_, r)| r.split_once("```"))
        .unwrap_or_else(|| panic!("README has no recipe after \"{intro}\""))
        .0;
    // The script's commands, not its `echo` banners or comments.
    let ci: String = read(".ci/run")
        .lines()
        .filter(|l| !l.trim_start().starts_with("echo ") && !l.trim_start().starts_with('#'))
        .map(|l| l.replace("./target/release/mbdbench", "mbdbench") + "\n")
        .collect();
    let mut at = 0;
    let mut n = 0;
    for line in block.lines() {
        // A loop's body is the command; its `$(...)` only lists the cases.
        let line = line.split_once("; do ").map_or(line, |(_, body)| body);
        for command in line
            .split(" && ")
            .map(|c| c.trim_end_matches("; done").trim())
        {
            let found = ci[at..].find(command).unwrap_or_else(|| {
                panic!("README's recipe: `{command}` is not in .ci/run after the previous one")
            });
            at += found + command.len();
            n += 1;
        }
    }
    assert!(n >= 10, "the recipe holds only {n} commands");
}

#[test]
fn the_slug_rule_is_githubs() {
    assert_eq!(slug("advise --json"), "advise---json");
    assert_eq!(slug("summary.json"), "summaryjson");
    assert_eq!(
        slug("Rigid-body keys (model = \"rigid_body\")"),
        "rigid-body-keys-model--rigid_body"
    );
    assert_eq!(slug("The stability study"), "the-stability-study");
    let twice = "# A\n\n## Notes\n\n## Notes\n";
    assert!(anchors(twice).contains("notes-1"));
}
