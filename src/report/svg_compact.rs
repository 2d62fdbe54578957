//! Smaller SVG from plotters: its backend writes every grid line, tick and axis segment as a
//! `<line>` element of its own, with the full style repeated (`opacity`, `stroke`,
//! `stroke-width`, about 100 bytes each; 137 of them in a work-precision plot, 60 % of its
//! bytes). `merge_lines` replaces each run of consecutive `<line>` elements with the same
//! style by one `<path>` whose `d` holds every segment (`M x1 y1 L x2 y2`, or `V`/`H` for the
//! vertical and horizontal ones). Drawing order is kept (only neighbours merge), so the
//! picture is the same pixel for pixel; a line whose attributes are not in plotters' form, and
//! anything inside a group (the data layer's series), is left as it is. `trim_defaults` then
//! drops default attributes and hoists the font to the root; `simplify_polyline` drops the
//! points of a data line that draw nothing.
//!
//! # Example
//!
//! ```
//! use mbdbench::report::svg_compact::merge_lines;
//!
//! let svg = "<svg>\n<line opacity=\"1\" stroke=\"#EEEEEE\" stroke-width=\"1\" x1=\"5\" y1=\"9\" x2=\"5\" y2=\"1\"/>\n\
//!            <line opacity=\"1\" stroke=\"#EEEEEE\" stroke-width=\"1\" x1=\"7\" y1=\"9\" x2=\"7\" y2=\"1\"/>\n</svg>\n";
//! assert_eq!(
//!     merge_lines(svg),
//!     "<svg>\n<path opacity=\"1\" stroke=\"#EEEEEE\" stroke-width=\"1\" fill=\"none\" d=\"M5 9V1M7 9V1\"/>\n</svg>\n"
//! );
//! ```

/// A parsed `<line opacity=.. stroke=.. stroke-width=.. x1=.. y1=.. x2=.. y2=../>`: its style
/// (the text before `x1`) and its end points (as written).
fn parse(line: &str) -> Option<(&str, [&str; 4])> {
    let body = line.trim().strip_prefix("<line ")?.strip_suffix("/>")?;
    let at = body.find(" x1=\"")?;
    let (style, coords) = (&body[..at], &body[at + 1..]);
    let mut xs = [""; 4];
    let mut rest = coords;
    for (k, key) in ["x1=\"", "y1=\"", "x2=\"", "y2=\""].iter().enumerate() {
        rest = rest.trim_start().strip_prefix(key)?;
        let end = rest.find('"')?;
        let v = &rest[..end];
        if v.is_empty() || !v.chars().all(|c| c.is_ascii_digit() || "-.".contains(c)) {
            return None;
        }
        xs[k] = v;
        rest = &rest[end + 1..];
    }
    if !rest.trim().is_empty() || style.contains(['<', '>']) {
        return None;
    }
    Some((style, xs))
}

/// A parsed `<polyline fill="none" STYLE points="x,y x,y ... "/>`: its style (without the
/// fill) and its points in path syntax (`Mx yLx y...`).
fn parse_polyline(line: &str) -> Option<(&str, String)> {
    let body = line
        .trim()
        .strip_prefix("<polyline fill=\"none\" ")?
        .strip_suffix("\"/>")?;
    let at = body.find(" points=\"")?;
    let (style, points) = (&body[..at], &body[at + 9..]);
    if style.contains(['<', '>']) {
        return None;
    }
    let mut d = String::new();
    for (k, p) in points.split_whitespace().enumerate() {
        let (x, y) = p.split_once(',')?;
        let num =
            |v: &str| !v.is_empty() && v.chars().all(|c| c.is_ascii_digit() || "-.".contains(c));
        if !(num(x) && num(y)) {
            return None;
        }
        d.push_str(&format!("{}{x} {y}", if k == 0 { "M" } else { "L" }));
    }
    (!d.is_empty()).then_some((style, d))
}

/// One segment in path syntax.
fn segment([x1, y1, x2, y2]: [&str; 4]) -> String {
    if x1 == x2 {
        format!("M{x1} {y1}V{y2}")
    } else if y1 == y2 {
        format!("M{x1} {y1}H{x2}")
    } else {
        format!("M{x1} {y1}L{x2} {y2}")
    }
}

/// The SVG with runs of same-style `<line>` elements merged into `<path>` elements.
pub fn merge_lines(svg: &str) -> String {
    let mut out = String::with_capacity(svg.len() / 2);
    let mut run: Option<(&str, String, usize)> = None;
    let flush = |out: &mut String, run: &mut Option<(&str, String, usize)>| {
        if let Some((style, d, _)) = run.take() {
            out.push_str(&format!("<path {style} fill=\"none\" d=\"{d}\"/>\n"));
        }
    };
    // Only plotters' own elements merge: the data layer's series groups (`<g ...>`, drawn
    // by `chart`) keep their elements, which the browser self-test counts.
    let mut depth = 0usize;
    for line in svg.split_inclusive('\n') {
        let t = line.trim_start();
        if t.starts_with("<g") {
            depth += 1;
        } else if t.starts_with("</g>") {
            depth = depth.saturating_sub(1);
        }
        let parsed = if depth > 0 {
            None
        } else {
            parse(line)
                .map(|(style, xs)| (style, segment(xs)))
                .or_else(|| parse_polyline(line))
        };
        match parsed {
            Some((style, seg)) => match &mut run {
                Some((s, d, n)) if *s == style => {
                    d.push_str(&seg);
                    *n += 1;
                }
                _ => {
                    flush(&mut out, &mut run);
                    run = Some((style, seg, 1));
                }
            },
            None => {
                flush(&mut out, &mut run);
                out.push_str(line);
            }
        }
    }
    flush(&mut out, &mut run);
    out
}

/// Drops what SVG says by default or can say once: every ` opacity="1"` (the default
/// opacity) and every ` font-family="sans-serif"`, which moves to the root `<svg>` element
/// that every text inherits it from (inline in the page too, where the root's attribute
/// overrides the page's font). The picture is unchanged; about 12 % of a plot's bytes.
pub fn trim_defaults(svg: &str) -> String {
    const FONT: &str = " font-family=\"sans-serif\"";
    let had_font = svg.contains(FONT);
    let mut out = svg.replace(" opacity=\"1\"", "").replace(FONT, "");
    if had_font && let Some(i) = out.find("<svg") {
        out.insert_str(i + 4, FONT);
    }
    out
}

/// The pixel points of a polyline without those that draw nothing: repeats of the previous
/// point, and points on the straight segment between their neighbours (collinear, between
/// them). The drawn path is the same pixel for pixel.
pub fn simplify_polyline(pts: &[(i32, i32)]) -> Vec<(i32, i32)> {
    let mut out: Vec<(i32, i32)> = Vec::with_capacity(pts.len());
    for &q in pts {
        if out.last() == Some(&q) {
            continue;
        }
        while let [.., a, b] = out[..] {
            let cross = i64::from(b.0 - a.0) * i64::from(q.1 - a.1)
                - i64::from(b.1 - a.1) * i64::from(q.0 - a.0);
            let between = (a.0.min(q.0)..=a.0.max(q.0)).contains(&b.0)
                && (a.1.min(q.1)..=a.1.max(q.1)).contains(&b.1);
            if cross == 0 && between {
                out.pop();
            } else {
                break;
            }
        }
        out.push(q);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Default attributes go, the font moves to the root once, and nothing else changes.
    #[test]
    fn defaults_are_trimmed() {
        let svg = "<svg width=\"10\">\n<text x=\"1\" font-family=\"sans-serif\" opacity=\"1\">a</text>\n\
                   <path opacity=\"1\" d=\"M0 0\"/>\n</svg>\n";
        assert_eq!(
            trim_defaults(svg),
            "<svg font-family=\"sans-serif\" width=\"10\">\n<text x=\"1\">a</text>\n<path d=\"M0 0\"/>\n</svg>\n"
        );
        let plain = "<svg>\n<path d=\"M0 0\"/>\n</svg>\n";
        assert_eq!(trim_defaults(plain), plain);
    }

    /// Repeated and collinear-between points go; a turn, a reversal along the same line (the
    /// middle point is not between its neighbours) and the end points stay.
    #[test]
    fn polyline_keeps_every_drawn_pixel() {
        let pts = [
            (0, 0),
            (0, 0),
            (1, 1),
            (2, 2),
            (3, 2),
            (5, 2),
            (4, 2),
            (4, 7),
        ];
        assert_eq!(
            simplify_polyline(&pts),
            vec![(0, 0), (2, 2), (5, 2), (4, 2), (4, 7)]
        );
        assert_eq!(simplify_polyline(&[(3, 4)]), vec![(3, 4)]);
        assert!(simplify_polyline(&[]).is_empty());
    }

    /// Same-style neighbours merge in order; a different style, any other element between
    /// them, or a line in another form breaks the run; diagonal segments use `L`.
    #[test]
    fn merges_only_same_style_neighbours() {
        let l = |s: &str, c: [i32; 4]| {
            format!(
                "<line opacity=\"1\" stroke=\"{s}\" stroke-width=\"1\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>\n",
                c[0], c[1], c[2], c[3]
            )
        };
        let svg = [
            l("#000", [0, 0, 10, 0]),
            l("#000", [1, 2, 3, 4]),
            l("#111", [5, 5, 5, 9]),
            "<text x=\"1\">a</text>\n".to_string(),
            l("#111", [6, 5, 6, 9]),
            "<line x1=\"1\" y1=\"2\" x2=\"3\" y2=\"4\" stroke=\"#000\"/>\n".to_string(),
        ]
        .concat();
        let m = merge_lines(&svg);
        assert_eq!(
            m,
            "<path opacity=\"1\" stroke=\"#000\" stroke-width=\"1\" fill=\"none\" d=\"M0 0H10M1 2L3 4\"/>\n\
             <path opacity=\"1\" stroke=\"#111\" stroke-width=\"1\" fill=\"none\" d=\"M5 5V9\"/>\n\
             <text x=\"1\">a</text>\n\
             <path opacity=\"1\" stroke=\"#111\" stroke-width=\"1\" fill=\"none\" d=\"M6 5V9\"/>\n\
             <line x1=\"1\" y1=\"2\" x2=\"3\" y2=\"4\" stroke=\"#000\"/>\n"
        );
        // Unfilled polylines (ticks, axes) merge with lines of the same style.
        let ticks = "<polyline fill=\"none\" opacity=\"1\" stroke=\"#3C3C3C\" stroke-width=\"1\" points=\"73,34 73,367 \"/>\n\
                     <line opacity=\"1\" stroke=\"#3C3C3C\" stroke-width=\"1\" x1=\"68\" y1=\"367\" x2=\"73\" y2=\"367\"/>\n";
        assert_eq!(
            merge_lines(ticks),
            "<path opacity=\"1\" stroke=\"#3C3C3C\" stroke-width=\"1\" fill=\"none\" d=\"M73 34L73 367M68 367H73\"/>\n"
        );
        // A filled polyline is not merged.
        let filled = "<polyline fill=\"#fff\" points=\"1,2 3,4 \"/>\n";
        assert_eq!(merge_lines(filled), filled);
        // Inside a group (a data series) nothing merges.
        let series = "<g class=\"series\">\n<polyline fill=\"none\" stroke=\"#000\" points=\"1,2 3,4 \"/>\n<polyline fill=\"none\" stroke=\"#000\" points=\"5,6 7,8 \"/>\n</g>\n";
        assert_eq!(merge_lines(series), series);
        // Without lines the SVG is unchanged.
        let plain = "<svg>\n<text>x</text>\n</svg>\n";
        assert_eq!(merge_lines(plain), plain);
    }
}
