//! The report's visual encoding, fixed across every plot so a variant looks the same
//! everywhere: colour = integrator, marker = parameterization, line pattern = formulation
//! (the family's first formulation solid, its second dashed), all by the families' axis order.
//! One exception keeps two lines of a panel from sharing colour and pattern: in a panel where
//! one integrator and formulation are drawn on several charts, the pattern is that of the
//! line's chart and formulation within the panel (`patterns`), listed in its legend.
//!
//! The markers are grouped by family so a reader can tell the chart type at a glance:
//! triangles for the three Euler-angle charts, diamonds for the rotation vector (hollow) and
//! the SO(3) group chart (filled), circles for quaternions and squares for matrices (hollow:
//! additive, no projection; filled: projected after each step), a cross and a plus for the
//! two SE(3) charts (the rigid family's chart order). Colours follow the integrator order of
//! `catalogue::axis_names` (every family's integrators in table order; a categorical palette
//! chosen for contrast on white), markers its parameterization order. A name past the palette
//! gets a colour from a hash of its name: stable, but possibly shared.
//!
//! Colour stays = integrator everywhere (a variant looks the same in every panel); the palette
//! is chosen so that any two integrators that can share a panel (a panel of a family's
//! selections, two methods of one kind, the quick stability study's three) differ by
//! CIEDE2000 >= 20 (`colour::delta_e`, tested below). The Kahan twins, which share panels
//! only with their own kind in the long-horizon plots, got dark teal, dark brown and dark sea
//! green (their light tints of the base colours were 13 to 19 apart from them).
use plotters::style::RGBColor;

use crate::catalogue::axis_position;
use crate::problem::Axis;

/// A marker shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    TriangleUp,
    TriangleDown,
    TriangleRight,
    DiamondHollow,
    DiamondFilled,
    CircleHollow,
    CircleFilled,
    SquareHollow,
    SquareFilled,
    Cross,
    Plus,
    TriangleUpHollow,
}

/// The parameterization markers, in `axis_names(Axis::Param)` order.
const PARAM_MARKERS: [Marker; 11] = [
    Marker::TriangleUp,    // euler_xyz
    Marker::TriangleDown,  // euler_zyx
    Marker::TriangleRight, // euler_zxz
    Marker::DiamondHollow, // rotvec
    Marker::CircleHollow,  // quat
    Marker::CircleFilled,  // quat_proj
    Marker::SquareHollow,  // matrix
    Marker::SquareFilled,  // matrix_proj
    Marker::DiamondFilled, // so3
    Marker::Cross,         // se3_hq
    Marker::Plus,          // dual_quat
];

fn hash(name: &str) -> usize {
    // FNV-1a: deterministic across runs and platforms.
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in name.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0100_0000_01b3);
    }
    h as usize
}

/// The colour of an integrator (ink for a plot's reference line): the colour the first family
/// in the table declaring it gives it (`problem::figures::Figures::colours`), else one derived
/// from its name ([`name_colour`]).
pub fn colour(integrator: &str) -> RGBColor {
    if integrator == super::timeseries::REFERENCE {
        return INK;
    }
    crate::catalogue::FAMILIES
        .iter()
        .flat_map(|f| f.figures.colours)
        .find(|(n, _)| *n == integrator)
        .map_or_else(
            || name_colour(integrator),
            |(_, [r, g, b])| RGBColor(*r, *g, *b),
        )
}

/// A colour of its own for a name no family declares (a method a user registers): a hue from
/// the name's hash (FNV-1a, the same on every machine and run), at a saturation and lightness
/// that read on white (HSL 0.65, 0.42).
pub fn name_colour(name: &str) -> RGBColor {
    let hue = (hash(name) % 360) as f64;
    let (s, l) = (0.65, 0.42);
    let c = (1.0 - (2.0 * l - 1.0_f64).abs()) * s;
    let x = c * (1.0 - ((hue / 60.0) % 2.0 - 1.0).abs());
    let (r, g, b) = match (hue / 60.0) as u32 {
        0 => (c, x, 0.0),
        1 => (x, c, 0.0),
        2 => (0.0, c, x),
        3 => (0.0, x, c),
        4 => (x, 0.0, c),
        _ => (c, 0.0, x),
    };
    let m = l - c / 2.0;
    let byte = |v: f64| ((v + m) * 255.0).round().clamp(0.0, 255.0) as u8;
    RGBColor(byte(r), byte(g), byte(b))
}

/// The marker of a parameterization.
pub fn marker(param: &str) -> Marker {
    match axis_position(Axis::Param, param) {
        i if i < PARAM_MARKERS.len() => PARAM_MARKERS[i],
        _ => Marker::TriangleUpHollow,
    }
}

/// A text glyph for a marker (the page's HTML legends): the same shape, filled or hollow.
pub fn glyph(m: Marker) -> char {
    match m {
        Marker::TriangleUp => '▲',
        Marker::TriangleDown => '▼',
        Marker::TriangleRight => '▶',
        Marker::DiamondHollow => '◇',
        Marker::DiamondFilled => '◆',
        Marker::CircleHollow => '○',
        Marker::CircleFilled => '●',
        Marker::SquareHollow => '□',
        Marker::SquareFilled => '■',
        Marker::Cross => '×',
        Marker::Plus => '+',
        Marker::TriangleUpHollow => '△',
    }
}

/// Whether a formulation's lines are dashed: the second (fourth, ...) formulation of its
/// family's axis is, the first (third, ...) and unknown ones are solid (the rigid body:
/// `body` solid, `spatial` dashed).
pub fn dashed(formulation: &str) -> bool {
    crate::catalogue::FAMILIES
        .iter()
        .find_map(|f| f.axes.formulations.iter().position(|x| *x == formulation))
        .is_some_and(|i| i % 2 == 1)
}

/// The line patterns, as SVG `stroke-dasharray` values (None: solid): 0 and 1 are the
/// formulations' (`dashed`), the rest tell apart lines of one panel that would otherwise share
/// colour and pattern (`patterns`).
pub const PATTERNS: [Option<&str>; 8] = [
    None,
    Some("6 4"),
    Some("2 3"),
    Some("9 3 2 3"),
    Some("14 4"),
    Some("9 3 2 3 2 3"),
    Some("2 7"),
    Some("4 2"),
];

/// The line patterns of one panel (`patterns`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Patterns {
    /// Per line, an index into [`PATTERNS`].
    pub lines: Vec<usize>,
    /// Empty where the patterns are the formulations' (`dashed`); else the panel's
    /// `(param, formulation)` pairs in first-seen order, each with its own pattern.
    pub pairs: Vec<(String, String, usize)>,
}

/// The pattern of each line of one panel, given per line `(integrator, param,
/// formulation)`: its formulation's (`dashed`: 1, else 0), unless two lines of one colour
/// (integrator) would then share a pattern (one integrator and formulation on several
/// charts, told apart only by their markers); then every line's pattern is that of its
/// `(param, formulation)` pair, the k-th pair of the panel taking pattern k, so lines of one
/// colour always differ in pattern (a panel draws at most 8 lines, `select`; past
/// `PATTERNS.len()` pairs the last pattern repeats).
pub fn patterns<'a>(keys: impl IntoIterator<Item = (&'a str, &'a str, &'a str)>) -> Patterns {
    let keys: Vec<(&str, &str, &str)> = keys.into_iter().collect();
    let base: Vec<usize> = keys.iter().map(|k| usize::from(dashed(k.2))).collect();
    let clash = keys.iter().enumerate().any(|(i, a)| {
        keys[i + 1..]
            .iter()
            .zip(&base[i + 1..])
            .any(|(b, &pb)| a.0 == b.0 && base[i] == pb)
    });
    if !clash {
        return Patterns {
            lines: base,
            pairs: vec![],
        };
    }
    let mut pairs: Vec<(String, String, usize)> = vec![];
    let lines = keys
        .iter()
        .map(|&(_, param, formulation)| {
            match pairs.iter().find(|p| p.0 == param && p.1 == formulation) {
                Some(p) => p.2,
                None => {
                    let k = pairs.len().min(PATTERNS.len() - 1);
                    pairs.push((param.to_string(), formulation.to_string(), k));
                    k
                }
            }
        })
        .collect();
    Patterns { lines, pairs }
}

/// `#rrggbb`.
pub fn hex(c: RGBColor) -> String {
    format!("#{:02x}{:02x}{:02x}", c.0, c.1, c.2)
}

/// The colour used for neutral ink (axes, legend markers of the parameterization key).
pub const INK: RGBColor = RGBColor(60, 60, 60);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::catalogue::axis_names;

    /// The pairs of integrators that can share a panel: those admitted together by a panel
    /// of a family's selections, every two of one kind (the long-horizon and crowded
    /// stability plots are split by kind, twins included), and the quick stability study's
    /// integrators (drawn together in its ladder plots).
    fn panel_pairs() -> Vec<(&'static str, &'static str)> {
        use crate::catalogue::FAMILIES;
        use crate::problem::matrix::registered;
        use crate::report::select::{kind_of, panels};
        let methods = crate::catalogue::methods();
        let mut sets: Vec<Vec<&'static str>> = vec![];
        for family in FAMILIES {
            for &sel in family.figures.selections() {
                for p in panels(sel, family) {
                    let mut set: Vec<&'static str> = registered(family)
                        .filter(|v| {
                            sel.admit.admits(v.param, v.integrator, v.info.adaptive)
                                && v.info.twin_of.is_none()
                                && p.admits_key(v.param, v.info.kind, v.formulation)
                        })
                        .map(|v| v.integrator)
                        .collect();
                    set.dedup();
                    sets.push(set);
                }
            }
        }
        for kind in crate::integrate::MethodKind::ALL {
            sets.push(
                axis_names(Axis::Integrator)
                    .iter()
                    .copied()
                    .filter(|i| kind_of(&methods, i) == kind)
                    .collect(),
            );
        }
        sets.push(crate::model::rigid_body::stability::QUICK_INTEGRATORS.to_vec());
        let mut pairs = vec![];
        for set in sets {
            for (i, a) in set.iter().enumerate() {
                for b in &set[i + 1..] {
                    if a != b && !pairs.contains(&(*a, *b)) && !pairs.contains(&(*b, *a)) {
                        pairs.push((*a, *b));
                    }
                }
            }
        }
        pairs
    }

    /// Any two integrator colours that can share a panel differ by CIEDE2000 >= 20 (clearly
    /// distinct side by side), and every colour stands off the white background.
    #[test]
    fn panel_colours_are_distinguishable() {
        use crate::report::colour::delta_e;
        let pairs = panel_pairs();
        assert!(pairs.len() > 10, "{pairs:?}");
        let close: Vec<String> = pairs
            .iter()
            .map(|(a, b)| (a, b, delta_e(colour(a), colour(b))))
            .filter(|(_, _, d)| *d < 20.0)
            .map(|(a, b, d)| format!("{a}/{b}: {d:.1}"))
            .collect();
        assert!(close.is_empty(), "dE2000 < 20: {close:?}");
        for i in axis_names(Axis::Integrator) {
            let d = delta_e(colour(i), plotters::style::RGBColor(255, 255, 255));
            assert!(d >= 20.0, "{i} on white: {d:.1}");
        }
    }

    /// No two lines of a panel share colour and pattern while it has at most
    /// `PATTERNS.len()` lines, whatever their integrators, charts and formulations.
    #[test]
    fn panel_lines_differ_in_colour_or_pattern() {
        let ints = ["rk4", "gauss6"];
        let params = ["quat", "so3", "rotvec", "matrix"];
        let forms = ["body", "spatial"];
        // Panels of up to 8 distinct variants drawn from 2 x 4 x 2 (every 7th subset).
        let mut all: Vec<(&str, &str, &str)> = vec![];
        for i in ints {
            for p in params {
                for f in forms {
                    all.push((i, p, f));
                }
            }
        }
        for mask in 1u32..(1 << all.len()) {
            if mask.count_ones() > 8 || mask % 7 != 0 {
                continue;
            }
            let keys: Vec<_> = (0..all.len())
                .filter(|b| mask >> b & 1 == 1)
                .map(|b| all[b])
                .collect();
            let p = patterns(keys.iter().copied());
            for (i, a) in keys.iter().enumerate() {
                for (j, b) in keys.iter().enumerate().skip(i + 1) {
                    assert!(
                        a.0 != b.0 || p.lines[i] != p.lines[j],
                        "{keys:?} -> {:?}",
                        p.lines
                    );
                }
            }
        }
    }

    /// Every integrator a family registers has a colour its family (or an earlier one)
    /// declares, and a name no family declares gets a colour of its own from its name alone:
    /// the same on every call, distinct for two names, never the ink of reference lines.
    #[test]
    fn colours_are_declared_by_name() {
        for f in crate::catalogue::FAMILIES {
            for i in f.axes.integrators {
                assert!(
                    crate::catalogue::FAMILIES.iter().any(|g| g
                        .figures
                        .colours
                        .iter()
                        .any(|(n, _)| n == i)),
                    "{}: no family declares a colour for `{i}`",
                    f.model
                );
            }
        }
        let (a, b) = (colour("my_users_method"), colour("another_method"));
        assert_eq!(a, name_colour("my_users_method"));
        assert_eq!(a, colour("my_users_method"));
        assert_ne!(a, b);
        assert_ne!(a, INK);
    }

    /// Every registered integrator has its own colour and every parameterization its own marker.
    #[test]
    fn distinct_encodings() {
        let cs: Vec<_> = axis_names(Axis::Integrator)
            .iter()
            .map(|i| colour(i))
            .collect();
        for (i, a) in cs.iter().enumerate() {
            for b in &cs[i + 1..] {
                assert_ne!(a, b);
            }
        }
        let ms: Vec<_> = axis_names(Axis::Param)
            .iter()
            .take(PARAM_MARKERS.len())
            .map(|p| marker(p))
            .collect();
        for (i, a) in ms.iter().enumerate() {
            for b in &ms[i + 1..] {
                assert_ne!(a, b);
            }
        }
        assert!(dashed("spatial") && !dashed("body"));
        let p = patterns([
            ("rk4", "quat", "body"),
            ("rk4", "quat", "spatial"),
            ("gauss6", "quat", "body"),
        ]);
        assert_eq!((p.lines, p.pairs.len()), (vec![0, 1, 0], 0));
        let p = patterns([
            ("rk4", "quat", "body"),
            ("rk4", "so3", "body"),
            ("gauss6", "quat", "body"),
        ]);
        assert_eq!(p.lines, vec![0, 1, 0]);
        assert_eq!(p.pairs.len(), 2);
        assert_eq!(colour("not_a_method"), colour("not_a_method"));
    }
}
