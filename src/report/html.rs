//! `index.html`: one self-contained page (README.md, "The report"): inline CSS, every plot an inline `<svg>` element
//! with its legend as HTML beside it (`legend`; the rows reflow under the plot on a narrow
//! screen), no `src` attribute and no `href` but in-page anchors, no network. One small inline
//! script (`script::SCRIPT`) sorts the heat maps by a clicked column and, only when the URL
//! hash is `#selftest`, writes the layout facts the CI browser check reads; the page reads the
//! same without it. Each case is a `<section class="case" data-case=...>` whose parts carry
//! `data-section` names (`narrative`, `heatmaps`, `work-precision`, `convergence`,
//! `timeseries`, `failures`, `largest-step`, `matrix`, ...) so that `render_check` (and a CI
//! browser step) can find them; each figure is a `<figure data-plot=...>` holding an `<svg
//! data-lines=N>` (N: its series, at most `select::MAX_LINES`) or a `<p class="nodata">` (no
//! data, or one sentence in place of a plot at round-off). Every case section repeats the
//! environment line (commit, rustc, CPU, OS, date). Running text is escaped and its
//! `code` spans become `<code>` (`prose`): no literal markdown reaches the page.
//!
//! `render_check` is a small tag tokenizer (not a full HTML parser): it reads start tags and
//! their attributes (quoted or not), skips comments, and reports external references,
//! scripts with a source and embedded resources, event-handler attributes, `url(`/`@import`
//! in CSS, and missing sections.
use super::chart::{Entry, Rendered};
use super::explain::Explained;
use super::stability::StabilitySection;
use super::tables::{Table, Tone};
use super::{CaseSection, Figure, Page};

/// The `data-section`s every case section must contain.
pub const REQUIRED_SECTIONS: [&str; 7] = [
    "narrative",
    "work-precision",
    "convergence",
    "timeseries",
    "failures",
    "largest-step",
    "heatmap",
];

/// Escapes text for HTML content and attribute values.
pub fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            _ => o.push(c),
        }
    }
    o
}

fn env_p(env: &str) -> String {
    format!("<p class=\"env\">{}</p>\n", esc(env))
}

/// Running text for the page: escaped, with its `code` spans as `<code>` elements and any
/// `**` dropped (the same text is markdown in `summary.md`).
pub fn prose(s: &str) -> String {
    let e = esc(&s.replace("**", ""));
    let mut out = String::with_capacity(e.len());
    let mut open = false;
    for (i, part) in e.split('`').enumerate() {
        if i > 0 {
            out.push_str(if open { "</code>" } else { "<code>" });
            open = !open;
        }
        out.push_str(part);
    }
    if open {
        out.push_str("</code>");
    }
    out
}

/// The legend rows of a plot as an HTML list (the samples drawn with CSS borders and the
/// markers' glyphs, `style::glyph`).
pub fn legend(entries: &[Entry]) -> String {
    let mut s = String::from("<ul class=\"legend\">");
    for e in entries {
        match e {
            Entry::Heading(t) => s.push_str(&format!("<li class=\"lh\">{}</li>", esc(t))),
            Entry::Sample {
                colour,
                pattern,
                line,
                marker,
                text,
            } => {
                let hex = super::style::hex(*colour);
                // The colour once per row (`--c`): the sample's line and the marker take it;
                // solid and dashed are CSS borders, a panel's own patterns CSS gradients
                // (`css.rs`, `.ls.p2` to `.p7`, the dash arrays of `style::PATTERNS`).
                let sample = match (line, pattern) {
                    (false, _) => "<span class=\"ls none\"></span>".to_string(),
                    (true, 0) => "<span class=\"ls\"></span>".to_string(),
                    (true, 1) => "<span class=\"ls dash\"></span>".to_string(),
                    (true, k) => format!("<span class=\"ls p{k}\"></span>"),
                };
                // Ink is the rows' default colour (`css.rs`), and a row without a marker
                // has no marker cell: the rows under one heading stay aligned.
                let style = if *colour == super::style::INK {
                    String::new()
                } else {
                    format!(" style=\"--c:{hex}\"")
                };
                let glyph = marker.map_or(String::new(), |m| {
                    format!("<span class=\"lm\">{}</span>", super::style::glyph(m))
                });
                s.push_str(&format!("<li{style}>{sample}{glyph}{}</li>", esc(text)));
            }
        }
    }
    s.push_str("</ul>");
    s
}

/// An inline SVG with its line count as `data-lines` on the root element.
fn with_lines(svg: &str, lines: usize) -> String {
    match svg.strip_prefix("<svg ") {
        Some(rest) => format!("<svg data-lines=\"{lines}\" {rest}"),
        None => svg.to_string(),
    }
}

fn figure(f: &Figure, caption: &str) -> String {
    let body = match &f.body {
        Rendered::Svg(d) => format!(
            "<div class=\"plotrow\">\n<div class=\"plot\">{}</div>\n{}\n</div>",
            with_lines(&d.inline, d.lines),
            legend(&d.legend)
        ),
        Rendered::NoData(why) => format!("<p class=\"nodata\">{}</p>", esc(why)),
        Rendered::Note(why) => format!("<p class=\"nodata roundoff\">{}</p>", esc(why)),
    };
    // The title above the plot in HTML (it wraps; the inline chart has none of its own).
    format!(
        "<figure data-plot=\"{}\">\n<div class=\"ptitle\">{}</div>\n{body}\n<figcaption>{}</figcaption>\n</figure>\n",
        esc(&f.kind),
        esc(&f.title),
        prose(caption)
    )
}

fn tone_class(t: Tone) -> &'static str {
    match t {
        Tone::Plain => "",
        Tone::Neutral => " class=\"neutral\"",
        Tone::Pass => " class=\"pass\"",
        Tone::Fail => " class=\"fail\"",
    }
}

/// Renders a table (long ones folded in a `<details>`).
pub fn table(t: &Table, open_below: usize) -> String {
    let fold = t.rows.len() > open_below;
    let mut s = format!("<div data-section=\"{}\">\n", t.kind);
    if fold {
        // Folded: the title is the summary, the note and the rows open on demand.
        s.push_str(&format!(
            "<details><summary>{} ({})</summary>\n<p>{}</p>\n",
            esc(&t.title),
            crate::summary::count(t.rows.len(), "row"),
            prose(&t.note)
        ));
    } else {
        s.push_str(&format!(
            "<h3>{}</h3>\n<p>{}</p>\n",
            esc(&t.title),
            prose(&t.note)
        ));
    }
    if t.rows.is_empty() {
        s.push_str("<p class=\"nodata\">no rows</p>\n</div>\n");
        return s;
    }
    s.push_str("<div class=\"tablewrap\">\n<table>\n<thead><tr>");
    for h in &t.header {
        s.push_str(&format!("<th>{}</th>", esc(h)));
    }
    s.push_str("</tr></thead>\n<tbody>\n");
    for row in &t.rows {
        s.push_str("<tr>");
        for (i, c) in row.iter().enumerate() {
            let msg = t
                .header
                .get(i)
                .is_some_and(|h| h == "message" || h == "note");
            let class = if msg && c.tone == Tone::Plain {
                " class=\"msg\""
            } else {
                tone_class(c.tone)
            };
            let title = c
                .full
                .as_ref()
                .map(|f| format!(" title=\"{}\"", esc(f)))
                .unwrap_or_default();
            s.push_str(&format!("<td{class}{title}>{}</td>", esc(&c.text)));
        }
        s.push_str("</tr>\n");
    }
    s.push_str("</tbody>\n</table>\n</div>\n");
    if fold {
        s.push_str("</details>\n");
    }
    s.push_str("</div>\n");
    s
}

/// How a figure's caption is written: its family's explanations (`explain`) and the kind of
/// plot it is.
#[derive(Clone, Copy)]
struct Captions<'a> {
    explained: &'a Explained,
    family: &'a str,
}

impl Captions<'_> {
    fn of(&self, kind: &str, f: &Figure) -> String {
        self.explained.caption(self.family, kind, &f.caption)
    }
}

/// A `data-section` of figures; `kind` is the kind of plot their captions are explained under.
fn figures(section: &str, kind: &str, title: &str, figs: &[Figure], cap: Captions) -> String {
    let mut s = format!(
        "<div data-section=\"{section}\">\n<h3>{}</h3>\n",
        esc(title)
    );
    if figs.is_empty() {
        s.push_str("<p class=\"nodata\">no data</p>\n");
    }
    s.push_str("<div class=\"figs\">\n");
    for f in figs {
        s.push_str(&figure(f, &cap.of(kind, f)));
    }
    s.push_str("</div>\n</div>\n");
    s
}

/// A folded part of a case: `<details data-section=...>` with a one-line summary.
fn fold(section: &str, summary: &str, body: &str) -> String {
    format!(
        "<details class=\"part\" data-section=\"{section}\">\n<summary>{}</summary>\n{body}</details>\n",
        esc(summary)
    )
}

/// The stability study's part of a case (`data-section="stability"`, its tables and plots
/// inside with their own `data-section`s).
fn stability_part(st: &StabilitySection, cap: Captions) -> String {
    let mut s = String::from(
        "<details data-section=\"stability\" class=\"stability part\">\n<summary>Stability \
         study</summary>\n",
    );
    s.push_str(&env_p(&st.env_line));
    s.push_str("<ul class=\"narrative\">\n");
    for sentence in &st.text {
        s.push_str(&format!("<li>{}</li>\n", prose(sentence)));
    }
    s.push_str("</ul>\n");
    for t in st.steps.iter().filter(|t| t.open) {
        s.push_str(&table(&t.table, 0));
    }
    let generated: Vec<_> = st.steps.iter().filter(|t| !t.open).collect();
    if !generated.is_empty() {
        s.push_str(&format!(
            "<details><summary>{} generated scenes (stiffness ladder): their step tables</summary>\n",
            generated.len()
        ));
        for t in generated {
            s.push_str(&table(&t.table, 0));
        }
        s.push_str("</details>\n");
    }
    if !st.ladder.is_empty() {
        s.push_str(&figures(
            "stability-ladder",
            "stability",
            "Stiffness ladder: largest steps against the stiffness factor",
            &st.ladder,
            cap,
        ));
    }
    if !st.long_horizon.is_empty() {
        s.push_str(&figures(
            "stability-long-horizon-plots",
            "stability",
            "Long horizon: energy and momentum error over time",
            &st.long_horizon,
            cap,
        ));
    }
    if !st.singularity.is_empty() {
        s.push_str(&figures(
            "stability-singularity",
            "stability",
            "Singularity ladder: error, work and conditioning against the approach distance",
            &st.singularity,
            cap,
        ));
    }
    if !st.sensitivity.is_empty() {
        s.push_str(&figures(
            "stability-sensitivity",
            "stability",
            "Sensitivity: growth of an initial perturbation",
            &st.sensitivity,
            cap,
        ));
    }
    for t in [&st.long_table, &st.other, &st.other_fits]
        .into_iter()
        .flatten()
    {
        s.push_str(&table(t, 0));
    }
    s.push_str("</details>\n");
    s
}

fn case_section(c: &CaseSection, env: &str, explained: &Explained) -> String {
    let cap = Captions {
        explained,
        family: c.family,
    };
    let mut s = format!(
        "<section class=\"case\" data-case=\"{}\" id=\"{}\">\n<h2>{}{}</h2>\n",
        esc(&c.name),
        esc(&super::advice::anchor(&c.name)),
        esc(&c.name),
        if c.title.is_empty() {
            String::new()
        } else {
            format!(" &mdash; {}", esc(&c.title))
        }
    );
    s.push_str(&env_p(env));
    s.push_str(
        "<div data-section=\"narrative\" class=\"narrative\">\n<h3>What this shows</h3>\n<ul>\n",
    );
    for sentence in &c.narrative {
        s.push_str(&format!("<li>{}</li>\n", prose(sentence)));
    }
    s.push_str("</ul>\n</div>\n");
    if let Some(g) = &c.gates {
        s.push_str(&table(g, 0));
    }
    if !c.scenes.is_empty() {
        let maps: String = c
            .scenes
            .iter()
            .enumerate()
            .map(|(i, sc)| super::heatmap::html(&sc.heat, i == 0))
            .collect();
        s.push_str(&fold(
            "heatmaps",
            &format!(
                "Heat maps: variants x metrics, one per scene ({})",
                crate::summary::count(c.scenes.len(), "scene")
            ),
            &maps,
        ));
    }
    if !c.across.is_empty() {
        s.push_str(&fold(
            "across",
            &format!("Across scenes ({} plots)", c.across.len()),
            &figures(
                "across-scenes",
                "across-scenes",
                "Across scenes",
                &c.across,
                cap,
            ),
        ));
    }
    for sc in &c.scenes {
        s.push_str(&format!(
            "<details class=\"scene\" data-section=\"scene\" data-scene=\"{}\">\n<summary>Scene {} ({} plots, {} variants)</summary>\n",
            esc(&sc.name),
            esc(&sc.name),
            sc.work_precision.len() + sc.convergence.len() + sc.timeseries.len(),
            sc.variants
        ));
        if let Some(n) = &sc.reference_note {
            s.push_str(&format!(
                "<p class=\"refvar\"><b>Reference = a variant.</b> {}</p>\n",
                esc(n)
            ));
        }
        s.push_str(&figures(
            "work-precision",
            "work-precision",
            &format!("{}: work-precision", sc.name),
            &sc.work_precision,
            cap,
        ));
        s.push_str(&figures(
            "convergence",
            "convergence",
            &format!("{}: convergence", sc.name),
            &sc.convergence,
            cap,
        ));
        s.push_str(&figures(
            "timeseries",
            "timeseries",
            &format!("{}: {}", sc.name, timeseries_title(sc)),
            &sc.timeseries,
            cap,
        ));
        s.push_str("</details>\n");
    }
    if c.scenes.is_empty() {
        for kind in ["work-precision", "convergence", "timeseries", "heatmap"] {
            s.push_str(&format!(
                "<div data-section=\"{kind}\"><p class=\"nodata\">no data</p></div>\n"
            ));
        }
    }
    s.push_str(&table(&c.failures, 0));
    s.push_str(&table(&c.largest, 0));
    if let Some(st) = &c.stability {
        s.push_str(&stability_part(st, cap));
    }
    s.push_str(&table(&c.na, 0));
    s.push_str("</section>\n");
    s
}

/// The title of a scene's plots over time: what its family declares they draw
/// (`timeseries::section_title`).
fn timeseries_title(sc: &super::SceneSection) -> String {
    sc.timeseries_title.clone()
}

/// The whole page.
pub fn render(page: &Page) -> String {
    let mut s = String::from(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>mbdbench report</title>\n<style>",
    );
    s.push_str(super::css::CSS);
    s.push_str(&super::heatmap::css());
    s.push_str("</style>\n</head>\n<body>\n<header>\n<h1>mbdbench report</h1>\n");
    s.push_str(&env_p(&page.env_line));
    s.push_str(
        "<p class=\"key\">Every section is folded: open it on demand. Each family's plots are \
         explained once, in its \"How to read\" block before its first case.</p>\n",
    );
    if let Some(g) = &page.gate_summary {
        s.push_str(&format!(
            "<p class=\"gates\"><b>Gates:</b> {}.",
            esc(&g.line)
        ));
        for (why, k) in &g.skipped {
            s.push_str(&format!(" Skipped {k}: {}.", esc(why)));
        }
        s.push_str("</p>\n");
    }
    s.push_str("<p>Cases: ");
    let names: Vec<String> = page
        .cases
        .iter()
        .map(|c| format!("<b>{}</b>", esc(&c.name)))
        .collect();
    s.push_str(&if names.is_empty() {
        "none (no data)".to_string()
    } else {
        names.join(", ")
    });
    s.push_str(".</p>\n</header>\n");
    if let Some(a) = &page.advice {
        let order: Vec<(String, &str)> = page
            .cases
            .iter()
            .map(|c| (c.name.clone(), c.family))
            .collect();
        s.push_str(&super::advice::html(a, page.physical.as_ref(), &order));
    }
    let explained = Explained::of(page);
    let mut family = "";
    for c in &page.cases {
        if c.family != family {
            family = c.family;
            s.push_str(&explained.block(family));
        }
        s.push_str(&case_section(c, &page.env_line, &explained));
    }
    s.push_str("<script>");
    s.push_str(super::script::SCRIPT);
    s.push_str("</script>\n</body>\n</html>\n");
    s
}

/// One start tag: its name and attributes (names lower-cased).
#[derive(Debug, Clone, PartialEq)]
pub struct Tag {
    pub name: String,
    pub attrs: Vec<(String, String)>,
}

impl Tag {
    fn attr(&self, name: &str) -> Option<&str> {
        self.attrs
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }
}

/// The start tags of a document, in order (comments, end tags and doctype skipped).
pub fn start_tags(html: &str) -> Vec<Tag> {
    let b = html.as_bytes();
    let mut out = vec![];
    let mut i = 0;
    while i < b.len() {
        if b[i] != b'<' {
            i += 1;
            continue;
        }
        if html[i..].starts_with("<!--") {
            i = html[i..].find("-->").map(|k| i + k + 3).unwrap_or(b.len());
            continue;
        }
        i += 1;
        if i >= b.len() || !(b[i].is_ascii_alphabetic()) {
            continue;
        }
        let start = i;
        while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'>' && b[i] != b'/' {
            i += 1;
        }
        let name = html[start..i].to_ascii_lowercase();
        let mut attrs = vec![];
        loop {
            while i < b.len() && (b[i].is_ascii_whitespace() || b[i] == b'/') {
                i += 1;
            }
            if i >= b.len() || b[i] == b'>' {
                i += 1;
                break;
            }
            let a0 = i;
            while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'=' && b[i] != b'>' {
                i += 1;
            }
            let an = html[a0..i].to_ascii_lowercase();
            while i < b.len() && b[i].is_ascii_whitespace() {
                i += 1;
            }
            let mut value = String::new();
            if i < b.len() && b[i] == b'=' {
                i += 1;
                while i < b.len() && b[i].is_ascii_whitespace() {
                    i += 1;
                }
                if i < b.len() && (b[i] == b'"' || b[i] == b'\'') {
                    let q = b[i];
                    let v0 = i + 1;
                    let end = b[v0..]
                        .iter()
                        .position(|&c| c == q)
                        .map(|k| v0 + k)
                        .unwrap_or(b.len());
                    value = html[v0..end].to_string();
                    i = end + 1;
                } else {
                    let v0 = i;
                    while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'>' {
                        i += 1;
                    }
                    value = html[v0..i].to_string();
                }
            }
            attrs.push((an, value));
        }
        out.push(Tag { name, attrs });
    }
    out
}

/// Problems of a report page: external references (any `src`/`href`-like attribute, a
/// script, an embedded resource, a URL outside the SVG namespace declaration, CSS `url(` or
/// `@import`), a missing environment line, a case without one of `REQUIRED_SECTIONS`, a
/// figure with neither an `<svg>` nor a "no data" note. Empty when the page is fine.
pub fn render_check(html: &str) -> Vec<String> {
    let mut problems = vec![];
    let tags = start_tags(html);
    const REF_ATTRS: [&str; 9] = [
        "src",
        "href",
        "xlink:href",
        "srcset",
        "action",
        "formaction",
        "poster",
        "background",
        "data",
    ];
    const RESOURCE_TAGS: [&str; 8] = [
        "link", "iframe", "object", "embed", "img", "base", "image", "use",
    ];
    for t in &tags {
        // An inline script runs the page's own code; one with a source fetches it (its `src`
        // is reported below).
        if RESOURCE_TAGS.contains(&t.name.as_str()) {
            problems.push(format!(
                "<{}> element (script or external resource)",
                t.name
            ));
        }
        for (n, v) in &t.attrs {
            // A link inside the page (`href="#case-..."`, the recommendation's headings) fetches
            // nothing.
            let in_page = t.name == "a" && n == "href" && v.starts_with('#');
            if !in_page && (REF_ATTRS.contains(&n.as_str()) || n.ends_with(":href")) {
                problems.push(format!("<{}> has a {n}=\"{v}\" attribute", t.name));
            } else if n.starts_with("on") {
                problems.push(format!("<{}> has an event handler {n}", t.name));
            } else if n != "xmlns"
                && !n.starts_with("xmlns:")
                && (v.contains("http://") || v.contains("https://") || v.contains("url("))
            {
                problems.push(format!("<{}> {n}=\"{v}\" refers to a URL", t.name));
            }
        }
    }
    let lower = html.to_ascii_lowercase();
    if lower.contains("@import") {
        problems.push("CSS @import".into());
    }
    if lower.contains("url(") {
        problems.push("CSS url(...)".into());
    }
    if !tags.iter().any(|t| {
        t.attr("class")
            .is_some_and(|c| c.split(' ').any(|x| x == "env"))
    }) {
        problems.push("no environment line (class=\"env\")".into());
    }
    // Sections per case, and figure contents.
    let mut cases: Vec<(String, Vec<String>)> = vec![];
    // A figure holds an <svg> or a no-data note before its caption.
    let mut pending_figure: Option<String> = None;
    for t in &tags {
        if pending_figure.is_some() {
            let ok = t.name == "svg"
                || (t.name == "p" && t.attr("class").is_some_and(|c| c.contains("nodata")));
            if ok {
                pending_figure = None;
            } else if t.name == "figcaption" || t.name == "figure" {
                let p = pending_figure.take().unwrap_or_default();
                problems.push(format!(
                    "figure {p} has neither an <svg> nor a no-data note"
                ));
            }
        }
        if t.name == "section"
            && let Some(c) = t.attr("data-case")
        {
            cases.push((c.to_string(), vec![]));
        }
        if let Some(sec) = t.attr("data-section")
            && let Some(last) = cases.last_mut()
        {
            last.1.push(sec.to_string());
        }
        if t.name == "figure" {
            pending_figure = Some(t.attr("data-plot").unwrap_or("?").to_string());
        }
    }
    if let Some(p) = pending_figure {
        problems.push(format!(
            "figure {p} has neither an <svg> nor a no-data note"
        ));
    }
    if cases.is_empty() && !html.contains("none (no data)") {
        problems.push("no case section".into());
    }
    for (c, secs) in &cases {
        for req in REQUIRED_SECTIONS {
            if !secs.iter().any(|s| s == req) {
                problems.push(format!("case {c}: missing section {req}"));
            }
        }
    }
    problems
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tokenizer reads quoted, single-quoted and bare attributes and skips comments.
    #[test]
    fn tokenizer() {
        let t = start_tags("<!-- <img src=x> --><p class=\"a b\" id='q' hidden data-x=1>t</p>");
        assert_eq!(t.len(), 1);
        assert_eq!(t[0].name, "p");
        assert_eq!(t[0].attr("class"), Some("a b"));
        assert_eq!(t[0].attr("id"), Some("q"));
        assert_eq!(t[0].attr("hidden"), Some(""));
        assert_eq!(t[0].attr("data-x"), Some("1"));
    }

    /// External references and scripts are reported; the SVG namespace declaration and a
    /// link inside the page (`href="#..."`) are not.
    #[test]
    fn finds_external_refs() {
        let bad = "<p class=\"env\">x</p><a href=\"#x\">a</a><a href=\"https://e.org\">b</a>\
                   <img src=\"a.png\"><script src=\"s.js\"></script><script>1</script>\
                   <svg xmlns=\"http://www.w3.org/2000/svg\"><image xlink:href=\"b.png\"/></svg>\
                   <div style=\"background:url(c.png)\"></div>";
        let p = render_check(bad);
        let joined = p.join("\n");
        for want in [
            "href=\"https://e.org\"",
            "src=\"a.png\"",
            "<script> has a src=\"s.js\"",
            "xlink:href",
            "url(",
        ] {
            assert!(joined.contains(want), "{want} not reported in {joined}");
        }
        assert!(!joined.contains("xmlns"), "{joined}");
        assert!(!joined.contains("\"#x\""), "{joined}");
        // The inline script is not a problem: exactly one script is reported, the sourced one.
        assert_eq!(joined.matches("<script>").count(), 1, "{joined}");
    }

    /// A case without its sections, and a figure without content, are reported.
    #[test]
    fn finds_missing_sections() {
        let html = "<p class=\"env\">e</p><section class=\"case\" data-case=\"c\">\
                    <div data-section=\"narrative\"></div><figure data-plot=\"p\"><figcaption>x</figcaption></figure></section>";
        let p = render_check(html);
        assert!(
            p.iter().any(|s| s.contains("missing section heatmap")),
            "{p:?}"
        );
        assert!(!p.iter().any(|s| s.contains("missing section narrative")));
        assert!(
            p.iter().any(|s| s.contains("figure p has neither")),
            "{p:?}"
        );
    }
}
