//! Explanations written once per family: the plots of one family repeat the same caption
//! sentences (how to read a work-precision plot, which variants a selection draws, what the
//! line styles mean) on every scene of every case. Here every caption is split into sentences;
//! a sentence that two or more figures of the same family carry, under the same kind of plot
//! (work-precision, convergence, over time, across scenes, stability), is stated once in the
//! family's "How to read" block, under that kind, and left out of the captions. The family's
//! key (`problem::figures::Figures::key_text`) opens the block.
//!
//! Sentences that belong to one figure stay in its caption even when repeated: the panel it
//! draws (`This panel: ...`), the ladder point it shows, and what is missing or failed
//! (`No data`, `Failed`): moved away from their figure they would no longer say which plot
//! they describe.
use std::collections::{BTreeMap, BTreeSet};

use super::html::{esc, prose};
use super::{CaseSection, Figure, Page};

/// The kinds of plot, in the order the block lists them: (key, heading).
pub const KINDS: [(&str, &str); 5] = [
    ("work-precision", "Work-precision plots"),
    ("convergence", "Convergence plots"),
    ("timeseries", "Plots over time (or over the load path)"),
    ("across-scenes", "Plots across scenes"),
    ("stability", "Stability plots"),
];

/// Sentence openings that tie a sentence to its own figure (never moved).
const OWN: [&str; 5] = [
    "This panel",
    "Each variant at",
    "No data",
    "No series",
    "Failed",
];

/// Splits a caption into sentences: at ". " before an upper-case letter or a code span.
pub fn sentences(caption: &str) -> Vec<&str> {
    let b = caption.as_bytes();
    let mut out = vec![];
    let mut start = 0;
    let mut i = 0;
    while i + 2 < b.len() {
        if b[i] == b'.' && b[i + 1] == b' ' && (b[i + 2].is_ascii_uppercase() || b[i + 2] == b'`') {
            out.push(caption[start..=i].trim());
            start = i + 2;
            i += 2;
            continue;
        }
        i += 1;
    }
    let last = caption[start..].trim();
    if !last.is_empty() {
        out.push(last);
    }
    out
}

/// The figures of a case by kind.
fn figures_of(c: &CaseSection) -> Vec<(&'static str, &Figure)> {
    let mut out: Vec<(&'static str, &Figure)> = vec![];
    for s in &c.scenes {
        out.extend(s.work_precision.iter().map(|f| ("work-precision", f)));
        out.extend(s.convergence.iter().map(|f| ("convergence", f)));
        out.extend(s.timeseries.iter().map(|f| ("timeseries", f)));
    }
    out.extend(c.across.iter().map(|f| ("across-scenes", f)));
    if let Some(st) = &c.stability {
        out.extend(st.figures().map(|f| ("stability", f)));
    }
    out
}

/// The sentences stated once per family.
#[derive(Debug, Clone, Default)]
pub struct Explained {
    /// family -> kind -> sentences in first-seen order.
    moved: BTreeMap<&'static str, BTreeMap<&'static str, Vec<String>>>,
}

impl Explained {
    /// Finds the sentences to state once, per family and kind of plot.
    pub fn of(page: &Page) -> Explained {
        let mut seen: BTreeMap<(&'static str, &'static str, &str), usize> = BTreeMap::new();
        let mut order: Vec<(&'static str, &'static str, &str)> = vec![];
        for c in &page.cases {
            for (kind, f) in figures_of(c) {
                let unique: BTreeSet<&str> = sentences(&f.caption).into_iter().collect();
                for s in unique {
                    if OWN.iter().any(|o| s.starts_with(o)) {
                        continue;
                    }
                    let n = seen.entry((c.family, kind, s)).or_insert(0);
                    if *n == 0 {
                        order.push((c.family, kind, s));
                    }
                    *n += 1;
                }
            }
        }
        let mut moved: BTreeMap<&'static str, BTreeMap<&'static str, Vec<String>>> =
            BTreeMap::new();
        for k in order {
            if seen[&k] >= 2 {
                moved
                    .entry(k.0)
                    .or_default()
                    .entry(k.1)
                    .or_default()
                    .push(k.2.to_string());
            }
        }
        Explained { moved }
    }

    fn is_moved(&self, family: &str, kind: &str, sentence: &str) -> bool {
        self.moved
            .get(family)
            .and_then(|k| k.get(kind))
            .is_some_and(|v| v.iter().any(|s| s == sentence))
    }

    /// A figure's caption without the sentences stated in its family's block.
    pub fn caption(&self, family: &str, kind: &str, caption: &str) -> String {
        sentences(caption)
            .into_iter()
            .filter(|s| !self.is_moved(family, kind, s))
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// The family's "How to read" block (a `<details>`, `data-section="howto"`): its key,
    /// then per kind of plot the sentences its captions share.
    pub fn block(&self, family: &str) -> String {
        let key = crate::catalogue::FAMILIES
            .iter()
            .find(|f| f.model == family)
            .map_or("", |f| f.figures.key_text);
        let mut s = format!(
            "<details class=\"howto\" data-section=\"howto\" data-family=\"{}\">\n\
             <summary>How to read the {} plots (said once for all its cases)</summary>\n\
             <p class=\"key\">{}</p>\n",
            esc(family),
            esc(family),
            prose(key)
        );
        if let Some(kinds) = self.moved.get(family) {
            for (kind, heading) in KINDS {
                let Some(list) = kinds.get(kind) else {
                    continue;
                };
                s.push_str(&format!(
                    "<p><b>{heading}</b></p>\n<ul class=\"narrative\">\n"
                ));
                for sentence in list {
                    s.push_str(&format!("<li>{}</li>\n", prose(sentence)));
                }
                s.push_str("</ul>\n");
            }
        }
        s.push_str("</details>\n");
        s
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Captions split at sentence ends only: a decimal point, an abbreviation before a lower-case
    /// word and a final period without a space keep their sentence whole.
    #[test]
    fn splits_sentences() {
        let s = sentences("Error 1.5e-3 at t = 0.5 s. Lines: rk4, e.g. this. `x` is y. Last.");
        assert_eq!(
            s,
            vec![
                "Error 1.5e-3 at t = 0.5 s.",
                "Lines: rk4, e.g. this.",
                "`x` is y.",
                "Last."
            ]
        );
    }

    /// A sentence two figures of one family share under one kind is stated once in that
    /// family's block and leaves both captions; a sentence of one figure, a figure's own panel
    /// sentence, and the same sentence under another family stay where they are.
    #[test]
    fn shared_sentences_move_once() {
        let mut page = crate::report::fixture::page();
        let c = &mut page.cases[0];
        let sc = &mut c.scenes[0];
        assert!(sc.work_precision.len() >= 2, "the fixture draws two plots");
        for (i, f) in sc.work_precision.iter_mut().enumerate() {
            f.caption = format!("Shared sentence here. This panel: p{i}. Only in figure {i}.");
        }
        let family = c.family;
        let e = Explained::of(&page);
        let f0 = &page.cases[0].scenes[0].work_precision[0];
        let cap = e.caption(family, "work-precision", &f0.caption);
        assert_eq!(cap, "This panel: p0. Only in figure 0.");
        let block = e.block(family);
        assert_eq!(block.matches("Shared sentence here.").count(), 1, "{block}");
        assert!(!block.contains("This panel") && !block.contains("Only in figure"));
        // Under another kind or family nothing moved.
        assert_eq!(e.caption(family, "convergence", &f0.caption), f0.caption);
        assert_eq!(
            e.caption("other", "work-precision", &f0.caption),
            f0.caption
        );
    }
}
