//! The figures a model family declares for the report: which variants each plot draws (named
//! selections, with the caption sentence that names them), which work-precision, convergence,
//! time-series and across-scene plots a scene or case gets, how to read the markers, and the
//! group of parameterizations the narrative contrasts with the others (the rigid body's Euler
//! charts, with their singular sets). The report composes these declarations and names no
//! chart or integrator itself; a family without a declaration of some kind simply gets no plot
//! of that kind. A family's declaration starts from [`Figures::NONE`] (no plots) for every
//! field it does not set.
//!
//! The kinds are today's four (work-precision against wall time and RHS evaluations,
//! convergence over the fixed-step ladder, quantities over time (energy and constraint drift,
//! a family's own column against the reference, or against another column: an x-y curve such
//! as a hysteresis loop), a measure across the scenes of a case). A new kind is a new list
//! here and its composer in `src/report/`.
//!
//! # Example
//!
//! ```
//! use mbdbench::catalogue;
//! use mbdbench::problem::{self, figures::Admit};
//!
//! let fig = catalogue::FAMILIES[0].figures;
//! // Every work-precision selection draws something of the family's variant table.
//! for sel in fig.work_precision {
//!     let drawn = problem::matrix::registered(catalogue::FAMILIES[0])
//!         .filter(|v| sel.admit.admits(v.param, v.integrator, v.info.adaptive))
//!         .count();
//!     assert!(drawn > 0, "{}", sel.id);
//! }
//! assert!(Admit::Adaptive.admits("any", "any", true));
//! ```
use super::Axis;

/// Which variants a selection admits.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Admit {
    /// Every variant with this integrator.
    Integrator(&'static str),
    /// Every variant on this parameterization.
    Param(&'static str),
    /// Every adaptive variant.
    Adaptive,
    /// Every variant.
    All,
}

impl Admit {
    /// Whether the variant `(param, integrator)`, adaptive or not, is admitted.
    pub fn admits(self, param: &str, integrator: &str, adaptive: bool) -> bool {
        match self {
            Admit::Integrator(i) => integrator == i,
            Admit::Param(p) => param == p,
            Admit::Adaptive => adaptive,
            Admit::All => true,
        }
    }
}

/// A named selection of variants: what a plot draws and how its caption says so.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Selection {
    /// A short id for file names (`wp_wall_<id>`).
    pub id: &'static str,
    /// A title fragment.
    pub short: &'static str,
    /// The caption sentence naming what is drawn (each plot says whether as lines or dots, and
    /// what the line styles mean, from `Figures::line_styles`).
    pub describe: &'static str,
    pub admit: Admit,
    /// The axes a convergence legend names: those that vary within the selection.
    pub legend_axes: &'static [Axis],
    /// How the selection is split into panels of at most [`MAX_LINES`] lines each.
    pub split: Split,
}

/// The most lines one panel draws: beyond about eight, colours and markers stop being told
/// apart (the report's unit tests and the browser check hold every panel to it).
pub const MAX_LINES: usize = 8;

/// How a selection is split into panels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Split {
    /// One panel.
    Whole,
    /// One panel per integrator kind (`integrate::MethodKind`: explicit, implicit, geometric, structural).
    Kind,
    /// One panel per parameterization group (`Figures::param_groups`).
    ParamGroup,
    /// One panel per parameterization group and formulation.
    ParamGroupFormulation,
    /// One panel per formulation (a family whose formulations are its main axis).
    Formulation,
}

/// A group of parameterizations drawn in one panel.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ParamGroup {
    /// A short id for file names.
    pub id: &'static str,
    /// A title fragment and caption phrase (`Euler angles and rotvec`).
    pub label: &'static str,
    pub params: &'static [&'static str],
}

/// A quantity drawn over time from a run's series file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The relative energy drift (`metrics::energy_drift::relative`).
    Energy,
    /// The energy balance of a family whose series' `energy` is the balance's residual
    /// `E(t) = kinetic + recoverable strain + dissipated - input work` (zero at t = 0):
    /// `|E(t)| / energy_scale` on a log axis; `what` is the caption's sentence saying how
    /// the books are kept. Runs whose `energy` is not finite (no energy books: a scene
    /// without dynamics) have no line, and a scene where no run has one has no panel.
    /// `books` is the balance's formula as the family keeps it (`|E - W|`, `|K + U + D - W|`):
    /// the axis label and the caption name it.
    Balance {
        what: &'static str,
        books: &'static str,
    },
    /// The chart's constraint residual (absent for charts without one); `what` is the
    /// caption's sentence saying what it is for the family's charts.
    Constraint { what: &'static str },
    /// A family's own quantity from the series' `tracks[column]` on a linear axis, against
    /// the reference's `tracks[reference]` (an ink line): one panel per group of
    /// formulations, one line per formulation (its first variant in the family's order, on
    /// an integrator no other line of the panel uses when it can, at that variant's coarsest
    /// completed ladder point); `what` is the caption's sentence, `id` the file-name stem,
    /// `y_label` the axis label. The selection it is declared with only says which variants
    /// keep their series.
    Track {
        column: &'static str,
        reference: &'static str,
        id: &'static str,
        what: &'static str,
        y_label: &'static str,
        groups: &'static [FormulationGroup],
        /// Against another column instead of time: `(column, its reference, axis label)`
        /// (a hysteresis loop: the base shear against the top's displacement).
        x: Option<(&'static str, &'static str, &'static str)>,
    },
}

/// Formulations drawn in one panel of a `Quantity::Track` plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FormulationGroup {
    /// A short id for file names.
    pub id: &'static str,
    /// A title fragment.
    pub label: &'static str,
    pub formulations: &'static [&'static str],
}

/// What an across-scenes plot measures per scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// The case's primary error metric.
    Primary,
    /// A metric of the records, with the plot's id and the caption's description.
    Metric {
        name: &'static str,
        id: &'static str,
        what: &'static str,
    },
    /// RHS evaluations.
    RhsEvals,
}

/// A group of parameterizations the narrative contrasts with the others (failure rate, lowest
/// conditioning, adaptive cost against the same method on `compare_with`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ChartGroup {
    /// The group's parameterizations: names starting with this.
    pub prefix: &'static str,
    /// The group at the start of a sentence (`Euler-angle charts`).
    pub label: &'static str,
    /// One member in running text (`an Euler chart`).
    pub one: &'static str,
    /// The parameterization the group's adaptive cost is compared with.
    pub compare_with: &'static str,
}

impl ChartGroup {
    /// Whether `param` belongs to the group.
    pub fn contains(&self, param: &str) -> bool {
        param.starts_with(self.prefix)
    }
}

/// Everything a family declares for the report.
#[derive(Debug, Clone, Copy)]
pub struct Figures {
    /// How to read the plots' colours, markers and lines (page and markdown header).
    pub key_text: &'static str,
    /// Per scene: each selection against wall time, then against RHS evaluations.
    pub work_precision: &'static [Selection],
    /// Per scene: the fixed-step variants of each selection against their step.
    pub convergence: &'static [Selection],
    /// Per scene: each quantity over time, for each selection.
    pub timeseries: &'static [(Quantity, Selection)],
    /// Per case with several scenes: each measure across the scenes.
    pub across_scenes: &'static [(Selection, Measure)],
    /// The group the narrative contrasts, if any.
    pub chart_group: Option<ChartGroup>,
    /// The parameterization groups of `Split::ParamGroup` panels, in report order (a
    /// parameterization in none of them gets a panel of its own kind, "other charts").
    pub param_groups: &'static [ParamGroup],
    /// What the line styles mean in the line plots (e.g. "body formulation solid, spatial
    /// dashed"); the dot plots place a variant's formulations side by side instead.
    pub line_styles: &'static str,
    /// A variant with no completed run is drawn over time by its finest failed run, up to
    /// the failure (the beam's diverging `modal_linear`); otherwise failed runs are left out
    /// of the time-series plots (and their series files are not written).
    pub draw_failed: bool,
    /// A family whose formulations differ in physics (the beam's modal, AIGC and FE forms)
    /// declares the metric against its physical reference: the report's first screen ranks
    /// the variants on it first (through `advise`, at `targets`), the primary metric's
    /// time-discretisation view second. None: the primary metric is the physical one.
    pub physical: Option<PhysicalView>,
    /// What a scene's `t` is, for the axes: (the label of `t`, the label of its step). Time in
    /// seconds for a dynamic scene (`seconds`); a static scene's load factor or a cyclic
    /// protocol's increments are not seconds, and their family says so.
    pub t_axis: fn(&crate::case::Scene) -> (&'static str, &'static str),
    /// The colours (RGB) of the family's integrators in every plot, by name. A name another
    /// family declared before it in the table keeps that family's colour (so a shared method
    /// looks the same in every family); a name no family declares (a method registered at
    /// run time) gets a colour derived from its name (`report::style::colour`).
    pub colours: &'static [(&'static str, [u8; 3])],
}

impl Figures {
    /// Every selection the family declares, in the order of the lists: work-precision,
    /// convergence, time series, across scenes.
    pub fn selections(&self) -> impl Iterator<Item = &'static Selection> {
        self.work_precision
            .iter()
            .chain(self.convergence)
            .chain(self.timeseries.iter().map(|(_, s)| s))
            .chain(self.across_scenes.iter().map(|(s, _)| s))
    }

    /// No plots: every list empty, no chart group, no physical view, failed runs left out,
    /// `t` in seconds, no colours of the family's own. A family declares the fields it uses
    /// and takes the rest from here (`..Figures::NONE`), so a new optional field is added
    /// here once, with the value that changes no family's report.
    pub const NONE: Figures = Figures {
        key_text: "",
        work_precision: &[],
        convergence: &[],
        timeseries: &[],
        across_scenes: &[],
        chart_group: None,
        param_groups: &[],
        line_styles: "",
        draw_failed: false,
        physical: None,
        t_axis: seconds,
        colours: &[],
    };
}

/// `t` is time in seconds: `("t (s)", "step dt (s)")`.
pub fn seconds(_: &crate::case::Scene) -> (&'static str, &'static str) {
    (seconds_label(), "step dt (s)")
}

/// The label of `t` in seconds.
pub const fn seconds_label() -> &'static str {
    "t (s)"
}

/// The ranking against a family's physical reference (`Figures::physical`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalView {
    /// The metric measuring the distance to the physical reference (one of the family's).
    pub metric: &'static str,
    /// The target errors it is ranked at, in the metric's unit, largest first.
    pub targets: &'static [f64],
    /// One sentence saying what the ranking measures, for the first screen.
    pub what: &'static str,
    /// A target is offered where it is at least this many times every scene's reference
    /// error for `metric` (`Problem::physical_claim`): a ranking of models asks whether a
    /// target is met, decided to `1 / claim_margin` of it, not a step-convergence slope
    /// (whose floor is `advise::CLAIM_MARGIN`, 100).
    pub claim_margin: f64,
}
