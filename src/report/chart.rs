//! One plot as data (`Plot`: lines of variants, failure marks, axes, legend kind) and its
//! rendering to two SVG strings: the standalone file and the page's inline chart.
//!
//! Layout of the file (900 px wide, readable on a laptop): the chart on the left, the legend
//! in a 240 px column on the right (outside the data; up to 330 px for long per-line labels),
//! a one-line footer naming the commit and date. The inline chart is the same plot 560 px
//! wide without the legend: the page writes the legend rows (`Drawn::legend`) in HTML beside
//! it, where they reflow on a narrow screen. Each series is a `<g class="series">` and
//! `Drawn::lines` counts them (the page's `data-lines`). A category x axis (scene names) gets
//! dots only, never joined. A relative quantity whose every value is below `ROUND_OFF`
//! (`Plot::round_off`) is not drawn: one sentence with the bound computed from the data says
//! so (`Rendered::Note`).
//! plotters draws the frame: caption, grid, axes with the explicit ticks of `axes` (through a
//! small `Ranged` coordinate, `Ticked`), labels, legend text and footer. The data layer
//! (lines, markers, failure marks, legend samples) is written as SVG elements at plotters'
//! own pixel mapping (`ChartContext::backend_coord`) and appended on top: plotters' SVG
//! backend has no `stroke-dasharray` and its dashed series writes one element per dash (a
//! noisy round-off drift line became 12 000 elements, 1.2 MB), whereas one `<polyline>` per
//! line with a dash array stays small. Each line is drawn in its integrator's colour with its
//! parameterization's marker, dashed for the second formulation, and with a pattern of its
//! own where a panel would otherwise hold two lines of one colour and pattern (`style`). Runs that failed
//! have no value: their markers sit in a shaded "failed" band above the data, at their x
//! (the x range follows the lines; a mark outside it, or one that cannot be shown such as 0
//! RHS evaluations on a log axis, is pinned to the nearest edge), stacked when they coincide.
//!
//! Text: without plotters' `ttf`/`ab_glyph` features the SVG backend writes `<text>` elements
//! and sizes them with a crude estimate (0.7 em per character); the browser renders them with
//! its own sans-serif font. That estimate only affects plotters' label spacing, so no font
//! dependency is needed.
//!
//! Legends: `Factored` lists the encodings present (integrator colours, parameterization
//! markers, formulation line patterns): compact however many lines there are. `PerLine` lists
//! every line with its own text (used where each line carries a number, e.g. a fitted order).
use plotters::coord::Shift;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::prelude::*;
use std::ops::Range;

use super::axes::AxisSpec;
use super::data::VariantKey;
use super::style::{self, INK, Marker};
use crate::catalogue::axis_position;
use crate::problem::Axis;

/// Total width of every plot (px).
pub const WIDTH: u32 = 900;
const LEGEND_W: u32 = 240;
/// The widest legend column (long per-line labels widen it, the chart gives way).
const LEGEND_W_MAX: u32 = 330;
const MIN_HEIGHT: u32 = 440;
const FOOTER_H: u32 = 18;
const ROW_H: i32 = 15;

/// One line of a plot.
#[derive(Debug, Clone)]
pub struct Line {
    pub key: VariantKey,
    /// (x, y) in data units, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Legend text for `Legend::PerLine` (default: the variant's label).
    pub label: Option<String>,
    /// Draw a marker on every `marker_every`-th point (1: all).
    pub marker_every: usize,
}

/// A run that failed at x (no y value).
#[derive(Debug, Clone)]
pub struct FailMark {
    pub key: VariantKey,
    pub x: f64,
}

/// Which legend to draw.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    Factored,
    PerLine,
}

/// A plot as data.
#[derive(Debug, Clone)]
pub struct Plot {
    /// File stem, unique within its case (e.g. `large/wp_wall_rk4`).
    pub id: String,
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x: super::axes::Scale,
    pub y: super::axes::Scale,
    pub lines: Vec<Line>,
    pub fails: Vec<FailMark>,
    pub legend: Legend,
    /// What the plot shows and how its lines were chosen (HTML figure caption).
    pub caption: String,
    /// Provenance line drawn under the chart.
    pub footer: String,
    /// For a relative quantity, what it is (`constraint residual of so3`): when every value
    /// is below `ROUND_OFF` the plot is replaced by one sentence saying so.
    pub round_off: Option<String>,
}

impl Plot {
    /// A plot of `lines` with one legend entry per line, no failure marks and no round-off
    /// note, captioned `caption` over `footer`; the caller names it and labels and scales its
    /// axes (`Plot { id, title, .., ..Plot::per_line(..) }`).
    pub fn per_line(lines: Vec<Line>, caption: String, footer: &str) -> Plot {
        Plot {
            id: String::new(),
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x: super::axes::Scale::Linear,
            y: super::axes::Scale::Linear,
            lines,
            fails: vec![],
            legend: Legend::PerLine,
            caption,
            footer: footer.into(),
            round_off: None,
        }
    }
}

/// A rendered plot, or why there is none.
#[derive(Debug, Clone, PartialEq)]
pub enum Rendered {
    Svg(Drawn),
    NoData(String),
    /// One sentence in place of a plot whose values are all at round-off.
    Note(String),
}

/// Error while drawing (a plotters backend error, as text).
#[derive(Debug, Clone, PartialEq)]
pub struct DrawError(pub String);

fn err<E: std::fmt::Display>(e: E) -> DrawError {
    DrawError(e.to_string())
}

fn axis_for(scale: &super::axes::Scale, values: &[f64]) -> Option<AxisSpec> {
    use super::axes::Scale;
    match scale {
        Scale::Log => AxisSpec::log(values.iter().copied()),
        Scale::Linear => AxisSpec::linear(values.iter().copied()),
        Scale::Category(names) => Some(AxisSpec::category(names.clone())),
    }
}

/// The width of a plot drawn inline in the page (its legend is HTML beside it).
pub const INLINE_WIDTH: u32 = 560;
const INLINE_HEIGHT: u32 = 400;
/// Every value of a plot with `round_off` below this is at round-off (relative quantities).
pub const ROUND_OFF: f64 = 1e-14;

/// A drawn plot.
#[derive(Debug, Clone, PartialEq)]
pub struct Drawn {
    /// The standalone SVG file: the chart with its own legend.
    pub file: String,
    /// The chart for the page, without the legend (the page writes it in HTML beside it).
    pub inline: String,
    /// Series drawn (variants with at least one point on the axes).
    pub lines: usize,
    /// The legend's rows (the page's HTML legend).
    pub legend: Vec<Entry>,
}

/// The smallest `m e k` (m a digit 1..9) strictly above `x > 0`: "stays below 3e-16" for a
/// largest value of 2.2e-16.
pub fn bound_above(x: f64) -> String {
    let e = x.log10().floor() as i32;
    let m = (x / 10f64.powi(e)).floor() as i32 + 1;
    if m >= 10 {
        format!("1e{}", e + 1)
    } else {
        format!("{m}e{e}")
    }
}

/// Draws a plot; `NoData` when there is nothing to show, `Note` when every value of a
/// relative quantity is at round-off.
pub fn render(p: &Plot) -> Result<Rendered, DrawError> {
    // The x range follows the lines; failure marks outside it are pinned to its edges (a run
    // that failed at t = 0 took 1e-7 s and would squash the data otherwise).
    let mut xs: Vec<f64> = p
        .lines
        .iter()
        .flat_map(|l| l.points.iter().map(|q| q.0))
        .collect();
    if xs.is_empty() {
        xs = p.fails.iter().map(|f| f.x).collect();
    }
    let ys: Vec<f64> = p
        .lines
        .iter()
        .flat_map(|l| l.points.iter().map(|q| q.1))
        .collect();
    let x = axis_for(&p.x, &xs);
    let y = axis_for(&p.y, &ys);
    let shown = |l: &Line| {
        l.points.iter().any(|&(a, b)| {
            x.as_ref().and_then(|x| x.map(a)).is_some()
                && y.as_ref().and_then(|y| y.map(b)).is_some()
        })
    };
    let lines = p.lines.iter().filter(|l| shown(l)).count();
    if lines == 0 && p.fails.is_empty() {
        return Ok(Rendered::NoData(format!(
            "no data: none of the {} selected variants has a {} value to plot",
            p.lines.len(),
            if matches!(p.y, super::axes::Scale::Log) {
                "positive"
            } else {
                "finite"
            }
        )));
    }
    if let Some(what) = &p.round_off {
        let top = ys
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |a, v| a.max(v.abs()));
        if p.fails.is_empty() && top > 0.0 && top < ROUND_OFF {
            return Ok(Rendered::Note(format!(
                "{what} stays below {} in every drawn run ({lines} variant{}): at \
                 round-off, so there is nothing to plot.",
                bound_above(top),
                if lines == 1 { "" } else { "s" }
            )));
        }
    }
    let Some(x) = x.or_else(|| AxisSpec::log([1.0, 10.0])) else {
        return Ok(Rendered::NoData("no data".into()));
    };
    let mut y = match y {
        Some(y) => y,
        None => AxisSpec::log([1e-3, 1.0]).ok_or_else(|| DrawError("axis".into()))?,
    };
    if !p.fails.is_empty() {
        y = y.with_fail_band();
    }
    let entries = legend_entries(p);
    let height = MIN_HEIGHT.max((entries.len() as i32 * ROW_H + 40) as u32 + FOOTER_H);
    let file = draw(p, &x, &y, (WIDTH, height), Some(&entries))?;
    // The page's copy: no footer (the page states the environment once per case) and the
    // page's shorter syntax (`svg_page`).
    let inline = super::svg_page::compact(&draw(p, &x, &y, (INLINE_WIDTH, INLINE_HEIGHT), None)?);
    Ok(Rendered::Svg(Drawn {
        file,
        inline,
        lines,
        legend: entries,
    }))
}

/// One SVG of the plot at `size`, with the legend column when `entries` is given.
fn draw(
    p: &Plot,
    x: &AxisSpec,
    y: &AxisSpec,
    (width, height): (u32, u32),
    entries: Option<&[Entry]>,
) -> Result<String, DrawError> {
    let mut buf = String::new();
    let mut overlay = String::new();
    {
        let root = SVGBackend::with_string(&mut buf, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        // The inline chart (no legend column) leaves the footer to the page.
        let footer_h = if entries.is_some() { FOOTER_H } else { 0 };
        let (main, footer) = root.split_vertically(height - footer_h);
        match entries {
            Some(entries) => {
                let legend_w = legend_width(entries);
                let (plot_area, legend_area) = main.split_horizontally(width - legend_w);
                draw_chart(p, &plot_area, x, y, true, &mut overlay)?;
                draw_legend(
                    &legend_area,
                    (width - legend_w) as i32,
                    entries,
                    &mut overlay,
                )?;
            }
            None => draw_chart(p, &main, x, y, false, &mut overlay)?,
        }
        if entries.is_some() {
            footer
                .draw(&Text::new(
                    p.footer.clone(),
                    (8, 2),
                    font(10.0).color(&RGBColor(110, 110, 110)),
                ))
                .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    // The data layer goes on top of plotters' grid, axes and text.
    match buf.rfind("</svg>") {
        Some(end) => buf.insert_str(end, &overlay),
        None => return Err(DrawError("the SVG backend wrote no closing tag".into())),
    }
    // plotters writes a `<line>` per grid line and tick: merged into paths, about half the
    // bytes of a plot (`svg_compact`).
    Ok(super::svg_compact::trim_defaults(
        &super::svg_compact::merge_lines(&buf),
    ))
}

/// A sans-serif font of `px` pixels in the SVG (plotters writes `font-size` = size / 1.24).
fn font(px: f64) -> FontDesc<'static> {
    ("sans-serif", px * 1.24).into_font()
}

/// An SVG polyline through pixel points: solid, or patterned with `stroke-dasharray`
/// (`style::PATTERNS[pattern]`; one element however long the line; plotters' dashed series
/// writes one element per dash).
fn polyline_svg(pts: &[(i32, i32)], colour: RGBColor, width: u32, pattern: usize) -> String {
    let coords: Vec<String> = super::svg_compact::simplify_polyline(pts)
        .iter()
        .map(|(a, b)| format!("{a},{b}"))
        .collect();
    format!(
        "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"{width}\" \
         stroke-linejoin=\"round\"{} points=\"{}\"/>\n",
        style::hex(colour),
        match style::PATTERNS.get(pattern).copied().flatten() {
            Some(d) => format!(" stroke-dasharray=\"{d}\""),
            None => String::new(),
        },
        coords.join(" ")
    )
}

/// An SVG marker of radius `r` px centred on pixel `(cx, cy)`.
pub fn marker_svg(m: Marker, c: RGBColor, (cx, cy): (i32, i32), r: i32) -> String {
    let col = style::hex(c);
    let fill = format!("fill=\"{col}\" stroke=\"none\"");
    let line = format!("fill=\"white\" stroke=\"{col}\" stroke-width=\"1.6\"");
    let h = r * 4 / 5;
    let poly = |pts: &[(i32, i32)], attrs: &str| {
        let p: Vec<String> = pts
            .iter()
            .map(|(a, b)| format!("{},{}", cx + a, cy + b))
            .collect();
        format!("<polygon points=\"{}\" {attrs}/>\n", p.join(" "))
    };
    let path = |d: String| {
        format!("<path d=\"{d}\" fill=\"none\" stroke=\"{col}\" stroke-width=\"2\"/>\n")
    };
    match m {
        Marker::TriangleUp => poly(&[(0, -r), (r, h), (-r, h)], &fill),
        Marker::TriangleUpHollow => poly(&[(0, -r), (r, h), (-r, h)], &line),
        Marker::TriangleDown => poly(&[(0, r), (r, -h), (-r, -h)], &fill),
        Marker::TriangleRight => poly(&[(r, 0), (-h, -r), (-h, r)], &fill),
        Marker::DiamondFilled => poly(&[(0, -r - 1), (r, 0), (0, r + 1), (-r, 0)], &fill),
        Marker::DiamondHollow => poly(&[(0, -r - 1), (r, 0), (0, r + 1), (-r, 0)], &line),
        Marker::CircleFilled => format!("<circle cx=\"{cx}\" cy=\"{cy}\" r=\"{r}\" {fill}/>\n"),
        Marker::CircleHollow => format!("<circle cx=\"{cx}\" cy=\"{cy}\" r=\"{r}\" {line}/>\n"),
        Marker::SquareFilled => poly(&[(-h, -h), (h, -h), (h, h), (-h, h)], &fill),
        Marker::SquareHollow => poly(&[(-h, -h), (h, -h), (h, h), (-h, h)], &line),
        Marker::Cross => path(format!(
            "M{} {}L{} {}M{} {}L{} {}",
            cx - r,
            cy - r,
            cx + r,
            cy + r,
            cx - r,
            cy + r,
            cx + r,
            cy - r
        )),
        Marker::Plus => path(format!(
            "M{} {cy}L{} {cy}M{cx} {}L{cx} {}",
            cx - r,
            cx + r,
            cy - r,
            cy + r
        )),
    }
}

/// The names of a category axis under the ticks at `at(i)` (pixel position of item `i` on
/// the axis), on two alternating rows when the longest name is wider than the spacing
/// (estimated at 7 px per character of a 12 px sans-serif font).
fn category_labels(names: &[String], at: impl Fn(usize) -> (i32, i32)) -> String {
    let spacing = if names.len() > 1 {
        (at(1).0 - at(0).0).abs()
    } else {
        i32::MAX
    };
    let widest = names.iter().map(|n| n.chars().count()).max().unwrap_or(0) as i32 * 7;
    let stagger = widest + 6 > spacing;
    let mut s = String::new();
    for (i, n) in names.iter().enumerate() {
        let (px, py) = at(i);
        let dy = if stagger && i % 2 == 1 { 30 } else { 17 };
        s.push_str(&format!(
            "<text x=\"{px}\" y=\"{}\" text-anchor=\"middle\" font-family=\"sans-serif\" \
             font-size=\"12\" fill=\"{}\">{}</text>\n",
            py + dy,
            style::hex(INK),
            super::html::esc(n)
        ));
    }
    s
}

/// A plotters coordinate over an `AxisSpec`: linear in the transformed space, with exactly
/// the spec's ticks (plotters' `WithKeyPoints` over `f64` does not accept a label formatter,
/// this does).
struct Ticked<'a>(&'a AxisSpec);

impl Ranged for Ticked<'_> {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, v: &f64, limit: (i32, i32)) -> i32 {
        let f = (v - self.0.lo) / (self.0.hi - self.0.lo);
        limit.0 + (f * f64::from(limit.1 - limit.0)).round() as i32
    }

    fn key_points<H: KeyPointHint>(&self, hint: H) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.0.minor.clone()
        } else {
            self.0.major.clone()
        }
    }

    fn range(&self) -> Range<f64> {
        self.0.lo..self.0.hi
    }
}

/// Axes, grid, labels and the failed band with plotters; the lines, markers and failure marks
/// as SVG elements in `overlay`, at the chart's own pixel mapping. The title is drawn only
/// when `titled` (the file): the page writes it in HTML above the inline chart, where a long
/// title wraps instead of being clipped at the chart's width.
fn draw_chart(
    p: &Plot,
    area: &DrawingArea<SVGBackend, Shift>,
    x: &AxisSpec,
    y: &AxisSpec,
    titled: bool,
    overlay: &mut String,
) -> Result<(), DrawError> {
    let category = matches!(x.scale, super::axes::Scale::Category(_));
    let mut builder = ChartBuilder::on(area);
    if titled {
        builder.caption(&p.title, font(14.0).color(&INK));
    }
    let mut chart = builder
        .margin(10)
        .x_label_area_size(if category { 56 } else { 44 })
        .y_label_area_size(64)
        .build_cartesian_2d(Ticked(x), Ticked(y))
        .map_err(err)?;
    // Category names are written below (staggered when they would overlap).
    let xf = |v: &f64| if category { String::new() } else { x.label(*v) };
    let yf = |v: &f64| y.label(*v);
    chart
        .configure_mesh()
        .x_label_formatter(&xf)
        .y_label_formatter(&yf)
        .x_desc(p.x_label.as_str())
        .y_desc(p.y_label.as_str())
        .label_style(font(12.0).color(&INK))
        .axis_desc_style(font(12.5).color(&INK))
        .bold_line_style(RGBColor(205, 205, 205))
        .light_line_style(RGBColor(238, 238, 238))
        .axis_style(INK)
        .draw()
        .map_err(err)?;
    if let Some((start, _)) = y.fail_band {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x.lo, start), (x.hi, y.hi)],
                RGBColor(253, 232, 232).filled(),
            )))
            .map_err(err)?;
    }
    if let super::axes::Scale::Category(names) = &x.scale {
        overlay.push_str(&category_labels(names, |i| {
            chart.backend_coord(&(i as f64, y.lo))
        }));
    }
    let width = if p.lines.iter().map(|l| l.points.len()).max().unwrap_or(0) > 40 {
        1
    } else {
        2
    };
    let mut markers = String::new();
    let patterns = line_patterns(p);
    for (l, &pattern) in p.lines.iter().zip(&patterns.lines) {
        let pts: Vec<(i32, i32)> = l
            .points
            .iter()
            .filter_map(|&(a, b)| Some(chart.backend_coord(&(x.map(a)?, y.map(b)?))))
            .collect();
        if pts.is_empty() {
            continue;
        }
        let c = style::colour(&l.key.integrator);
        // One group per series (the page's self-test counts them); a category axis gets
        // dots only, as its points are not a continuous quantity.
        overlay.push_str(&format!(
            "<g class=\"series\" data-variant=\"{}\">\n",
            super::html::esc(&l.key.label())
        ));
        if pts.len() > 1 && !category {
            overlay.push_str(&polyline_svg(&pts, c, width, pattern));
        }
        overlay.push_str("</g>\n");
        let m = style::marker(&l.key.param);
        let every = l.marker_every.max(1);
        for (i, &q) in pts.iter().enumerate() {
            if i % every == 0 || i + 1 == pts.len() {
                markers.push_str(&marker_svg(m, c, q, if category { 5 } else { 4 }));
            }
        }
    }
    overlay.push_str(&markers);
    if let Some((_, mark)) = y.fail_band {
        // Marks at the same place are stacked vertically inside the band.
        let mut taken: std::collections::HashMap<i32, usize> = Default::default();
        for f in &p.fails {
            let fx = x.map(f.x).unwrap_or(x.lo).clamp(x.lo, x.hi);
            let c = style::colour(&f.key.integrator);
            let (px, py) = chart.backend_coord(&(fx, mark));
            let n = taken.entry(px / 4).or_default();
            let dy = [0, -10, 10, -20, 20][*n % 5];
            *n += 1;
            overlay.push_str(&marker_svg(
                style::marker(&f.key.param),
                c,
                (px, py + dy),
                5,
            ));
        }
    }
    Ok(())
}

/// One legend row.
#[derive(Debug, Clone, PartialEq)]
pub enum Entry {
    Heading(String),
    /// A line sample (colour, pattern: an index into `style::PATTERNS`, marker) and its text.
    Sample {
        colour: RGBColor,
        pattern: usize,
        /// Draw the line sample (not only the marker).
        line: bool,
        marker: Option<Marker>,
        text: String,
    },
}

/// The line patterns of `p` (`style::patterns`).
fn line_patterns(p: &Plot) -> style::Patterns {
    style::patterns(p.lines.iter().map(|l| {
        (
            l.key.integrator.as_str(),
            l.key.param.as_str(),
            l.key.formulation.as_str(),
        )
    }))
}

fn legend_entries(p: &Plot) -> Vec<Entry> {
    let mut out = vec![];
    let patterns = line_patterns(p);
    let keys: Vec<&VariantKey> = p
        .lines
        .iter()
        .map(|l| &l.key)
        .chain(p.fails.iter().map(|f| &f.key))
        .collect();
    match p.legend {
        Legend::PerLine => {
            for (l, &pattern) in p.lines.iter().zip(&patterns.lines) {
                out.push(Entry::Sample {
                    colour: style::colour(&l.key.integrator),
                    pattern,
                    line: true,
                    marker: Some(style::marker(&l.key.param)),
                    text: l.label.clone().unwrap_or_else(|| l.key.label()),
                });
            }
        }
        Legend::Factored => {
            let mut integrators: Vec<&str> = vec![];
            let mut params: Vec<&str> = vec![];
            let mut forms: Vec<&str> = vec![];
            let mut sorted = keys.clone();
            sorted.sort();
            for k in &sorted {
                if !integrators.contains(&k.integrator.as_str()) {
                    integrators.push(&k.integrator);
                }
                if !forms.contains(&k.formulation.as_str()) {
                    forms.push(&k.formulation);
                }
            }
            for k in &sorted {
                if !params.contains(&k.param.as_str()) {
                    params.push(&k.param);
                }
            }
            integrators.sort_by_key(|i| axis_position(Axis::Integrator, i));
            out.push(Entry::Heading("integrator (colour)".into()));
            for i in integrators {
                out.push(Entry::Sample {
                    colour: style::colour(i),
                    pattern: 0,
                    line: true,
                    marker: None,
                    text: i.into(),
                });
            }
            // Dots on a category axis have no line: a chart's formulations sit side by side.
            let category = matches!(p.x, super::axes::Scale::Category(_));
            // With the panel's own patterns, the parameterization/formulation rows below
            // carry the markers of the lines; only a failure mark's chart without a line is
            // listed here then.
            let own = !patterns.pairs.is_empty() && !category;
            params.retain(|q| !own || !patterns.pairs.iter().any(|p| p.0 == *q));
            if !params.is_empty() {
                out.push(Entry::Heading("parameterization (marker)".into()));
                for q in params {
                    out.push(Entry::Sample {
                        colour: INK,
                        pattern: 0,
                        line: false,
                        marker: Some(style::marker(q)),
                        text: q.into(),
                    });
                }
            }
            if !own {
                out.push(Entry::Heading(
                    if category {
                        "formulation (left to right)"
                    } else {
                        "formulation (line)"
                    }
                    .into(),
                ));
                for f in forms {
                    out.push(Entry::Sample {
                        colour: INK,
                        pattern: usize::from(style::dashed(f)),
                        line: !category,
                        marker: None,
                        text: f.into(),
                    });
                }
            } else {
                // One integrator on several charts: the line pattern is the chart and
                // formulation's in this panel (`style::patterns`).
                out.push(Entry::Heading(
                    "parameterization/formulation (marker, line)".into(),
                ));
                for (param, formulation, pattern) in &patterns.pairs {
                    out.push(Entry::Sample {
                        colour: INK,
                        pattern: *pattern,
                        line: true,
                        marker: Some(style::marker(param)),
                        text: format!("{param}/{formulation}"),
                    });
                }
            }
        }
    }
    if !p.fails.is_empty() {
        out.push(Entry::Heading("marks in the red band:".into()));
        out.push(Entry::Heading("runs that failed (no value)".into()));
    }
    out
}

/// The legend column's width: `LEGEND_W`, or wider (up to `LEGEND_W_MAX`) for long sample
/// texts (estimated at 6.6 px per character of the 12 px font, after the 48 px sample).
fn legend_width(entries: &[Entry]) -> u32 {
    let longest = entries
        .iter()
        .map(|e| match e {
            Entry::Sample { text, .. } => 48 + text.chars().count() as u32 * 66 / 10,
            Entry::Heading(t) => 8 + t.chars().count() as u32 * 66 / 10,
        })
        .max()
        .unwrap_or(0);
    (longest + 8).clamp(LEGEND_W, LEGEND_W_MAX)
}

fn draw_legend(
    area: &DrawingArea<SVGBackend, Shift>,
    x0: i32,
    entries: &[Entry],
    overlay: &mut String,
) -> Result<(), DrawError> {
    let mut y = 34;
    for e in entries {
        match e {
            Entry::Heading(t) => {
                area.draw(&Text::new(t.clone(), (8, y), font(12.0).color(&INK)))
                    .map_err(err)?;
            }
            Entry::Sample {
                colour,
                pattern,
                line,
                marker,
                text,
            } => {
                let mid = y + 7;
                if *line {
                    overlay.push_str(&polyline_svg(
                        &[(x0 + 12, mid), (x0 + 42, mid)],
                        *colour,
                        2,
                        *pattern,
                    ));
                }
                if let Some(m) = marker {
                    overlay.push_str(&marker_svg(*m, *colour, (x0 + 27, mid), 4));
                }
                area.draw(&Text::new(text.clone(), (48, y), font(12.0).color(&INK)))
                    .map_err(err)?;
            }
        }
        y += ROW_H;
    }
    Ok(())
}

#[cfg(test)]
#[path = "chart_tests.rs"]
mod tests;
