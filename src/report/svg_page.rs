//! The inline SVG of the page, smaller than the standalone file (`svg_compact` made both
//! smaller already): the page holds some 600 plots and must stay within its size budget, so
//! what the page's CSS or a shorter path syntax can say is said once.
//!
//! - the white background `<rect>` goes (the page's CSS paints plots white);
//! - a `<text>` loses its padding newlines, the default ink `fill="#3C3C3C"` and the tick
//!   labels' `font-size="12"` (the page's CSS gives every text without them that ink and
//!   size); the root loses its namespace (HTML places an inline `<svg>` in it) and its font
//!   family (the page's CSS sets it);
//! - a `<polyline>` becomes a `<path>` in relative coordinates (`M74 180l0-2 1-2`), and runs
//!   of same-style `<polygon>` or `<circle>` markers become one `<path>` each (a circle as two
//!   arcs): about a quarter of the bytes, the same picture;
//! - plotters' frame paths of one style (ticks drawn one by one between their labels) merge
//!   into the first path of that style; they never overlap the labels, so the picture is the
//!   same.
//!
//! The series groups (`<g class="series">`) and their count stay as they are: the browser
//! self-test counts them. An element not in the form written by `chart` is left unchanged.
use std::fmt::Write;

/// The page's version of an inline SVG.
pub fn compact(svg: &str) -> String {
    let lines: Vec<&str> = svg.lines().collect();
    let mut out: Vec<String> = Vec::with_capacity(lines.len());
    let mut run: Option<(String, String)> = None;
    let flush = |out: &mut Vec<String>, run: &mut Option<(String, String)>| {
        if let Some((style, d)) = run.take() {
            out.push(format!("<path{style} d=\"{d}\"/>"));
        }
    };
    let mut i = 0;
    while i < lines.len() {
        let l = lines[i];
        if i <= 2 && is_background(l) {
            i += 1;
            continue;
        }
        if l.starts_with("<text") && !l.ends_with("</text>") && lines.get(i + 2) == Some(&"</text>")
        {
            flush(&mut out, &mut run);
            out.push(format!(
                "{}{}</text>",
                l.replace(" fill=\"#3C3C3C\"", "")
                    .replace(" font-size=\"12\"", ""),
                lines[i + 1].trim()
            ));
            i += 3;
            continue;
        }
        if let Some((style, d)) = marker(l) {
            match &mut run {
                Some((s, path)) if *s == style => path.push_str(&d),
                _ => {
                    flush(&mut out, &mut run);
                    run = Some((style, d));
                }
            }
            i += 1;
            continue;
        }
        flush(&mut out, &mut run);
        out.push(polyline(l).unwrap_or_else(|| l.to_string()));
        i += 1;
    }
    flush(&mut out, &mut run);
    if let Some(root) = out.first_mut().filter(|r| r.starts_with("<svg ")) {
        *root = root
            .replace(" xmlns=\"http://www.w3.org/2000/svg\"", "")
            .replace(" font-family=\"sans-serif\"", "");
    }
    let mut s = merge_frame(out).join("\n");
    s.push('\n');
    s
}

/// plotters' white background rectangle.
fn is_background(l: &str) -> bool {
    l.starts_with("<rect x=\"0\" y=\"0\" ") && l.ends_with(" fill=\"#FFFFFF\" stroke=\"none\"/>")
}

/// The value of `name="..."` in an element and the element without it.
fn take_attr(el: &str, name: &str) -> Option<(String, String)> {
    let key = format!(" {name}=\"");
    let at = el.find(&key)?;
    let v0 = at + key.len();
    let end = v0 + el[v0..].find('"')?;
    Some((
        el[v0..end].to_string(),
        format!("{}{}", &el[..at], &el[end + 1..]),
    ))
}

/// A coordinate as written (an integer or a short decimal).
fn coord(v: &str) -> Option<f64> {
    let ok = !v.is_empty() && v.chars().all(|c| c.is_ascii_digit() || "-.".contains(c));
    ok.then(|| v.parse().ok()).flatten()
}

/// `x,y x,y ...` as path data in relative coordinates: `Mx0 y0l dx dy dx dy ...`.
fn relative(points: &str) -> Option<String> {
    let mut d = String::new();
    let mut last: Option<(f64, f64)> = None;
    for p in points.split_whitespace() {
        let (x, y) = p.split_once(',')?;
        let (x, y) = (coord(x)?, coord(y)?);
        match last {
            None => {
                let _ = write!(d, "M{x} {y}l");
            }
            Some((a, b)) => {
                let (dx, dy) = (x - a, y - b);
                if !d.ends_with('l') && dx >= 0.0 {
                    d.push(' ');
                }
                let _ = write!(d, "{dx}");
                if dy >= 0.0 {
                    d.push(' ');
                }
                let _ = write!(d, "{dy}");
            }
        }
        last = Some((x, y));
    }
    last?;
    Some(d.trim_end_matches('l').to_string())
}

/// A marker (`<polygon>` or `<circle>`) as (its style attributes, its path data).
fn marker(l: &str) -> Option<(String, String)> {
    let body = l.strip_suffix("/>")?;
    if let Some(rest) = body.strip_prefix("<polygon") {
        let (points, style) = take_attr(rest, "points")?;
        let d = relative(&points)?;
        return Some((style.trim_end().to_string(), format!("{d}z")));
    }
    let rest = body.strip_prefix("<circle")?;
    let (cx, rest) = take_attr(rest, "cx")?;
    let (cy, rest) = take_attr(&rest, "cy")?;
    let (r, style) = take_attr(&rest, "r")?;
    let (cx, cy, r) = (coord(&cx)?, coord(&cy)?, coord(&r)?);
    let d = format!(
        "M{} {cy}a{r} {r} 0 1 0 {} 0a{r} {r} 0 1 0 {} 0z",
        cx - r,
        2.0 * r,
        -2.0 * r
    );
    Some((style.trim_end().to_string(), d))
}

/// A `<polyline>` as a `<path>` in relative coordinates.
fn polyline(l: &str) -> Option<String> {
    let body = l.strip_prefix("<polyline")?.strip_suffix("/>")?;
    let (points, style) = take_attr(body, "points")?;
    let d = relative(&points)?;
    Some(format!("<path{} d=\"{d}\"/>", style.trim_end()))
}

/// plotters' frame paths (outside every group) of one style merged into the first of them.
fn merge_frame(lines: Vec<String>) -> Vec<String> {
    let mut out: Vec<String> = Vec::with_capacity(lines.len());
    // style -> index in `out` of its first path.
    let mut first: Vec<(String, usize)> = vec![];
    let mut depth = 0usize;
    for l in lines {
        if l.starts_with("<g") {
            depth += 1;
        } else if l.starts_with("</g>") {
            depth = depth.saturating_sub(1);
        }
        let parsed = (depth == 0)
            .then(|| {
                l.strip_prefix("<path ")?
                    .strip_suffix("\"/>")?
                    .split_once(" d=\"")
            })
            .flatten()
            .filter(|(style, _)| style.contains("fill=\"none\"") && !style.contains('<'));
        let Some((style, d)) = parsed else {
            out.push(l);
            continue;
        };
        match first.iter().find(|(s, _)| s == style) {
            Some((_, at)) => {
                let at = *at;
                let merged = out[at].strip_suffix("\"/>").unwrap_or(&out[at]).to_string();
                out[at] = format!("{merged}{d}\"/>");
            }
            None => {
                first.push((style.to_string(), out.len()));
                out.push(l);
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Each rewrite keeps the geometry: a polyline's relative path visits the same points, a
    /// run of same-style markers becomes one path, a circle two arcs of its radius around its
    /// centre, texts lose only their padding and default ink, and series groups stay.
    #[test]
    fn same_picture_fewer_bytes() {
        let svg = "<svg width=\"10\">\n<rect x=\"0\" y=\"0\" width=\"10\" height=\"10\" fill=\"#FFFFFF\" stroke=\"none\"/>\n\
<text x=\"1\" y=\"2\" fill=\"#3C3C3C\">\n1e-9\n</text>\n\
<path stroke=\"#3C3C3C\" fill=\"none\" d=\"M1 1L1 2\"/>\n\
<text x=\"3\" y=\"2\" fill=\"#6E6E6E\">\nfoot\n</text>\n\
<path stroke=\"#3C3C3C\" fill=\"none\" d=\"M3 1L3 2\"/>\n\
<g class=\"series\" data-variant=\"a\">\n\
<polyline fill=\"none\" stroke=\"#1f77b4\" points=\"74,180 75,176 73,181\"/>\n\
<polygon points=\"75,170 79,177 71,177\" fill=\"#1f77b4\" stroke=\"none\"/>\n\
<polygon points=\"149,221 153,228 145,228\" fill=\"#1f77b4\" stroke=\"none\"/>\n\
<circle cx=\"10\" cy=\"20\" r=\"4\" fill=\"white\" stroke=\"#1f77b4\"/>\n\
</g>\n</svg>\n";
        let c = compact(svg);
        assert!(!c.contains("<rect"), "{c}");
        assert!(c.contains("<text x=\"1\" y=\"2\">1e-9</text>"), "{c}");
        assert!(c.starts_with("<svg width=\"10\">"), "{c}");
        assert!(
            c.contains("<text x=\"3\" y=\"2\" fill=\"#6E6E6E\">foot</text>"),
            "{c}"
        );
        assert!(
            c.contains("<path stroke=\"#3C3C3C\" fill=\"none\" d=\"M1 1L1 2M3 1L3 2\"/>"),
            "{c}"
        );
        assert_eq!(c.matches("<path stroke=\"#3C3C3C\"").count(), 1, "{c}");
        assert!(
            c.contains("<path fill=\"none\" stroke=\"#1f77b4\" d=\"M74 180l1-4-2 5\"/>"),
            "{c}"
        );
        assert!(
            c.contains(
                "<path fill=\"#1f77b4\" stroke=\"none\" d=\"M75 170l4 7-8 0zM149 221l4 7-8 0z\"/>"
            ),
            "{c}"
        );
        assert!(
            c.contains("<path fill=\"white\" stroke=\"#1f77b4\" d=\"M6 20a4 4 0 1 0 8 0a4 4 0 1 0 -8 0z\"/>"),
            "{c}"
        );
        assert!(c.contains("<g class=\"series\" data-variant=\"a\">") && c.contains("</g>"));
        assert!(c.len() < svg.len());
    }
}
