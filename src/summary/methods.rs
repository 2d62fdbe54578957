//! The summary's `methods` table (docs/schemas.md, "Methods and families"): the facts of every
//! method registered in the catalogue a run was made with (`integrate::MethodInfo`), keyed by
//! integrator name, so that a reader takes a method's kind, order, twin and the rest from the
//! summary it was given instead of looking the name up in its own compiled-in table. The
//! catalogue gathers it (`catalogue::methods`); this file holds its form, its reading and its
//! checks.
//!
//! Invariants: an entry holds every fact (a missing one, a fact of the wrong type, an unknown
//! `kind` or an entry that is not an object is refused when the file is read, the message
//! naming the key `methods.<name>.<fact>`); keys unknown to this reader are ignored, as in the
//! rest of the summary (the schema grows by optional keys). Two facts depend on the chart a
//! method runs on (`CHART_FACTS`): `lie_group` (an explicit Runge-Kutta method is
//! Runge-Kutta-Munthe-Kaas on a Lie-group chart) and `symplectic` (the Gauss methods are
//! symplectic on a vector space, not as Runge-Kutta-Munthe-Kaas methods on a group). For each
//! the table holds whether it holds on any of the method's registrations and, in
//! `<fact>_params`, on which parameterizations; `Methods::check` refuses a table where the two
//! disagree. Where it fails: names are only checked for control characters, not against a
//! catalogue (a summary may come from another build's catalogue; that is the point of the
//! table), and a fact that a method states wrongly is carried as stated.
//!
//! # Example
//!
//! ```
//! use mbdbench::integrate::{MethodInfo, MethodKind};
//! use mbdbench::summary::methods::{MethodFacts, Methods};
//!
//! let info = MethodInfo::new("midpoint_user", MethodKind::Implicit, 2).with_implicit(true);
//! let mut table = Methods::default();
//! table.insert("midpoint_user", MethodFacts::of(&info, "quat"));
//! let text = serde_json::to_string(&table).unwrap();
//! let back: Methods = serde_json::from_str(&text).unwrap();
//! assert_eq!(back.get("midpoint_user").unwrap().kind, MethodKind::Implicit);
//! // A fact of the wrong type is refused, naming its key.
//! let bad = text.replace("\"order\":2", "\"order\":\"two\"");
//! let e = serde_json::from_str::<Methods>(&bad).unwrap_err().to_string();
//! assert!(e.contains("key `methods.midpoint_user.order`"), "{e}");
//! ```
use std::collections::BTreeMap;
use std::fmt;

use serde::de::{Error as _, MapAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize};
use serde_json::Value;

use super::Summary;
use crate::integrate::{MethodInfo, MethodKind};

/// The facts that depend on the chart a method runs on; each has its list of
/// parameterizations, `<fact>_params`.
pub const CHART_FACTS: [&str; 2] = ["symplectic", "lie_group"];

/// One method's facts as a summary holds them: `MethodInfo` without its name (the table's key),
/// owned, with the parameterizations on which each chart-dependent fact holds.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct MethodFacts {
    /// `explicit`, `implicit`, `geometric` or `structural` (`MethodKind::name`).
    pub kind: MethodKind,
    pub order: u32,
    pub stages: u32,
    pub implicit: bool,
    /// Whether the method is symplectic on any of its registrations.
    pub symplectic: bool,
    /// The parameterizations on which it is, in registration order (empty when on none).
    pub symplectic_params: Vec<String>,
    /// Whether the method runs on a Lie group on any of its registrations.
    pub lie_group: bool,
    /// The parameterizations on which it does, in registration order (empty when on none).
    pub lie_group_params: Vec<String>,
    pub energy_conserving: bool,
    pub adaptive: bool,
    /// The method this one differs from only in its summation (a Kahan twin), or null.
    pub twin_of: Option<String>,
}

impl MethodFacts {
    /// The facts of one registration, on parameterization `param`.
    pub fn of(info: &MethodInfo, param: &str) -> MethodFacts {
        let on = |holds: bool| {
            if holds {
                vec![param.to_string()]
            } else {
                vec![]
            }
        };
        MethodFacts {
            kind: info.kind,
            order: info.order,
            stages: info.stages,
            implicit: info.implicit,
            symplectic: info.symplectic,
            symplectic_params: on(info.symplectic),
            lie_group: info.lie_group,
            lie_group_params: on(info.lie_group),
            energy_conserving: info.energy_conserving,
            adaptive: info.adaptive,
            twin_of: info.twin_of.map(str::to_string),
        }
    }

    /// Adds another registration of the method, on `param`: a chart-dependent fact holds when
    /// it holds on any registration. Returns whether `info` states the other facts as these
    /// do (`agrees_with`); these are kept either way.
    pub fn add(&mut self, info: &MethodInfo, param: &str) -> bool {
        let agrees = self.agrees_with(info);
        for (flag, params, holds) in [
            (
                &mut self.symplectic,
                &mut self.symplectic_params,
                info.symplectic,
            ),
            (
                &mut self.lie_group,
                &mut self.lie_group_params,
                info.lie_group,
            ),
        ] {
            if holds && !params.iter().any(|p| p == param) {
                *flag = true;
                params.push(param.to_string());
            }
        }
        agrees
    }

    /// Whether `info` states the same facts as these, the chart-dependent ones (`CHART_FACTS`)
    /// aside.
    pub fn agrees_with(&self, info: &MethodInfo) -> bool {
        let mut other = MethodFacts::of(info, "");
        other.symplectic = self.symplectic;
        other.symplectic_params = self.symplectic_params.clone();
        other.lie_group = self.lie_group;
        other.lie_group_params = self.lie_group_params.clone();
        *self == other
    }

    /// Each chart-dependent fact with its parameterizations (`CHART_FACTS` order).
    pub fn chart_facts(&self) -> [(&'static str, bool, &[String]); 2] {
        [
            ("symplectic", self.symplectic, &self.symplectic_params),
            ("lie_group", self.lie_group, &self.lie_group_params),
        ]
    }

    /// Reads an entry of the table; the error names the key (`methods.<name>.<fact>`).
    fn from_value(name: &str, v: &Value) -> Result<MethodFacts, String> {
        let name = name.escape_debug().to_string();
        let Some(obj) = v.as_object() else {
            return Err(format!(
                "key `methods.{name}` is {v}, expected an object of the method's facts"
            ));
        };
        let get = |fact: &str| {
            obj.get(fact)
                .ok_or_else(|| format!("key `methods.{name}.{fact}` is missing"))
        };
        let wrong = |fact: &str, v: &Value, expected: &str| {
            format!("key `methods.{name}.{fact}` is {v}, expected {expected}")
        };
        let flag = |fact: &str| {
            let v = get(fact)?;
            v.as_bool().ok_or_else(|| wrong(fact, v, "true or false"))
        };
        let count = |fact: &str| {
            let v = get(fact)?;
            v.as_u64()
                .and_then(|n| u32::try_from(n).ok())
                .ok_or_else(|| wrong(fact, v, "a whole number"))
        };
        let kind_value = get("kind")?;
        let kinds = MethodKind::ALL
            .map(|k| format!("`{}`", k.name()))
            .join(", ");
        let kind = kind_value
            .as_str()
            .and_then(|s| MethodKind::ALL.into_iter().find(|k| k.name() == s))
            .ok_or_else(|| wrong("kind", kind_value, &format!("one of {kinds}")))?;
        let names = |fact: &str| {
            let v = get(fact)?;
            v.as_array()
                .and_then(|a| {
                    a.iter()
                        .map(|p| p.as_str().map(str::to_string))
                        .collect::<Option<Vec<_>>>()
                })
                .ok_or_else(|| wrong(fact, v, "a list of names"))
        };
        let twin = get("twin_of")?;
        let twin_of = match twin {
            Value::Null => None,
            Value::String(s) => Some(s.clone()),
            _ => return Err(wrong("twin_of", twin, "a name or null")),
        };
        Ok(MethodFacts {
            kind,
            order: count("order")?,
            stages: count("stages")?,
            implicit: flag("implicit")?,
            symplectic: flag("symplectic")?,
            symplectic_params: names("symplectic_params")?,
            lie_group: flag("lie_group")?,
            lie_group_params: names("lie_group_params")?,
            energy_conserving: flag("energy_conserving")?,
            adaptive: flag("adaptive")?,
            twin_of,
        })
    }
}

/// The table: integrator name -> facts, in name order.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct Methods(BTreeMap<String, MethodFacts>);

impl Methods {
    /// The facts of `integrator`, if the table has it.
    pub fn get(&self, integrator: &str) -> Option<&MethodFacts> {
        self.0.get(integrator)
    }

    /// Adds (or replaces) the facts of `integrator`.
    pub fn insert(&mut self, integrator: &str, facts: MethodFacts) {
        self.0.insert(integrator.to_string(), facts);
    }

    /// The entries in name order.
    pub fn iter(&self) -> impl Iterator<Item = (&str, &MethodFacts)> {
        self.0.iter().map(|(k, v)| (k.as_str(), v))
    }

    /// The number of methods.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether the table is empty.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// Adds the entries of `other` whose names this table lacks (a merged run keeps the facts
    /// of the runs it keeps).
    pub fn extend_missing(&mut self, other: &Methods) {
        for (k, v) in &other.0 {
            self.0.entry(k.clone()).or_insert_with(|| v.clone());
        }
    }

    /// What the reading cannot check: no name holds a control character (they reach the
    /// terminal and the report), a twin names an entry of the table, and a chart-dependent
    /// fact (`lie_group`, `symplectic`) is true exactly when its `<fact>_params` names a
    /// parameterization. The message names the key.
    pub fn check(&self) -> Result<(), String> {
        let control = |s: &str| s.chars().any(char::is_control);
        for (name, f) in &self.0 {
            if control(name) {
                return Err(format!(
                    "key `methods`: the name {name:?} holds a control character"
                ));
            }
            let key = |fact: &str| format!("key `methods.{name}.{fact}`");
            for (fact, holds, params) in f.chart_facts() {
                let list = key(&format!("{fact}_params"));
                if let Some(p) = params.iter().find(|p| control(p)) {
                    return Err(format!("{list} holds {p:?}: a control character in a name"));
                }
                if holds == params.is_empty() {
                    return Err(format!("{} is {holds} but {list} is {params:?}", key(fact)));
                }
            }
            if let Some(t) = &f.twin_of
                && !self.0.contains_key(t)
            {
                return Err(format!(
                    "{} is {t:?}, which has no entry in `methods`",
                    key("twin_of")
                ));
            }
        }
        Ok(())
    }

    /// The table as JSON with one method per line, indented by `indent` spaces (the summary's
    /// header, `Summary::to_json_lines`).
    pub fn to_json_lines(&self, indent: usize) -> Result<String, serde_json::Error> {
        if self.0.is_empty() {
            return Ok("{}".into());
        }
        let pad = " ".repeat(indent + 2);
        let lines = self
            .0
            .iter()
            .map(|(k, v)| {
                Ok(format!(
                    "{pad}{}: {}",
                    serde_json::to_string(k)?,
                    serde_json::to_string(v)?
                ))
            })
            .collect::<Result<Vec<_>, serde_json::Error>>()?;
        Ok(format!(
            "{{\n{}\n{}}}",
            lines.join(",\n"),
            " ".repeat(indent)
        ))
    }
}

/// A summary's `methods` table and `families` list, read from a file (`Summary::check`): the
/// table's own checks (`Methods::check`), every record's and fit's integrator has an entry in
/// it when it is present, and the `families` list names each family once, without a control
/// character. The message names the key.
pub(super) fn check_summary(s: &Summary) -> Result<(), String> {
    if let Some(fams) = &s.families {
        for (i, f) in fams.iter().enumerate() {
            if f.chars().any(char::is_control) {
                return Err(format!(
                    "key `families[{i}]` is {f:?}: a control character in a name"
                ));
            }
            if fams[..i].contains(f) {
                return Err(format!("key `families[{i}]`: `{f}` appears twice"));
            }
        }
    }
    let Some(table) = &s.methods else {
        return Ok(());
    };
    table.check()?;
    let keys = s
        .records
        .iter()
        .map(|r| ("records", &r.key))
        .chain(s.fits.iter().map(|f| ("fits", &f.key)));
    let mut index: BTreeMap<&str, usize> = BTreeMap::new();
    for (list, k) in keys {
        let i = index.entry(list).or_default();
        if table.get(&k.integrator).is_none() {
            return Err(format!(
                "{list}[{i}]: key `integrator` is {:?}, which has no entry in `methods`",
                k.integrator
            ));
        }
        *i += 1;
    }
    Ok(())
}

impl<'de> Deserialize<'de> for Methods {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Methods, D::Error> {
        d.deserialize_map(TableVisitor)
    }
}

/// Reads the table entry by entry, so that an error names the entry's key.
struct TableVisitor;

impl<'de> Visitor<'de> for TableVisitor {
    type Value = Methods;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an object keyed by integrator name (key `methods`)")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Methods, A::Error> {
        let mut out = BTreeMap::new();
        while let Some(name) = map.next_key::<String>()? {
            let value: Value = map.next_value()?;
            let facts = MethodFacts::from_value(&name, &value).map_err(A::Error::custom)?;
            if out.insert(name.clone(), facts).is_some() {
                return Err(A::Error::custom(format!(
                    "key `methods.{}` appears twice",
                    name.escape_debug()
                )));
            }
        }
        Ok(Methods(out))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An edit of a table's JSON.
    type Edit = Box<dyn Fn(&mut Value)>;

    /// A table of three methods: rk4 (Lie-group on so3), an implicit one and its twin.
    fn table() -> Methods {
        let mut t = Methods::default();
        let rk4 = MethodInfo::new("rk4", MethodKind::Explicit, 4).with_stages(4);
        let mut f = MethodFacts::of(&rk4, "quat");
        assert!(f.add(&rk4.with_lie_group(true), "so3"));
        t.insert("rk4", f);
        let g = MethodInfo::new("g", MethodKind::Implicit, 6)
            .with_implicit(true)
            .with_symplectic(true);
        t.insert("g", MethodFacts::of(&g, "quat"));
        t.insert("g_kahan", MethodFacts::of(&g.with_twin_of("g"), "quat"));
        t
    }

    /// A second registration adds the parameterizations of its chart-dependent facts (each
    /// once) and reports whether its other facts agree; the first registration's are kept.
    #[test]
    fn registrations_merge_by_chart() {
        let g = MethodInfo::new("g", MethodKind::Implicit, 2)
            .with_implicit(true)
            .with_symplectic(true);
        let mut f = MethodFacts::of(&g, "quat");
        let on_group = g.with_symplectic(false).with_lie_group(true);
        assert!(f.add(&on_group, "so3"));
        assert!(f.add(&on_group, "so3"));
        assert!(f.add(&g, "rotvec"));
        assert_eq!(f.symplectic_params, ["quat", "rotvec"]);
        assert_eq!(f.lie_group_params, ["so3"]);
        assert!(f.symplectic && f.lie_group);
        assert!(!f.add(&g.with_stages(2), "matrix"));
        assert_eq!(f.stages, 1);
    }

    /// The table reads back to itself, from the compact form and from one line per method.
    #[test]
    fn round_trip() {
        let t = table();
        let back: Methods = serde_json::from_str(&serde_json::to_string(&t).unwrap()).unwrap();
        assert_eq!(back, t);
        let lines = t.to_json_lines(2).unwrap();
        assert_eq!(lines.lines().count(), 2 + t.len());
        let back: Methods = serde_json::from_str(&lines).unwrap();
        assert_eq!(back, t);
        assert!(back.check().is_ok());
    }

    /// Every malformed entry is refused with a message naming its key: a missing fact, a
    /// fact of the wrong type, an unknown kind, an entry that is not an object; a table that
    /// is not an object names `methods`.
    #[test]
    fn malformed_entries_name_their_key() {
        let good = serde_json::to_value(table()).unwrap();
        let cases: Vec<(&str, Edit, &str)> = vec![
            (
                "missing",
                Box::new(|v| {
                    v["rk4"].as_object_mut().unwrap().remove("adaptive");
                }),
                "key `methods.rk4.adaptive` is missing",
            ),
            (
                "type",
                Box::new(|v| v["g"]["implicit"] = "yes".into()),
                "key `methods.g.implicit` is \"yes\", expected true or false",
            ),
            (
                "kind",
                Box::new(|v| v["g"]["kind"] = "magic".into()),
                "key `methods.g.kind` is \"magic\", expected one of `explicit`",
            ),
            (
                "negative order",
                Box::new(|v| v["rk4"]["order"] = (-4).into()),
                "key `methods.rk4.order` is -4, expected a whole number",
            ),
            (
                "not an object",
                Box::new(|v| v["rk4"] = 4.into()),
                "key `methods.rk4` is 4, expected an object",
            ),
            (
                "twin",
                Box::new(|v| v["g_kahan"]["twin_of"] = 1.into()),
                "key `methods.g_kahan.twin_of` is 1, expected a name or null",
            ),
            (
                "params",
                Box::new(|v| v["rk4"]["lie_group_params"] = serde_json::json!([3])),
                "key `methods.rk4.lie_group_params` is [3], expected a list of names",
            ),
        ];
        for (what, edit, says) in cases {
            let mut v = good.clone();
            edit(&mut v);
            let e = serde_json::from_value::<Methods>(v)
                .unwrap_err()
                .to_string();
            assert!(e.contains(says), "{what}: {e}");
        }
        let e = serde_json::from_str::<Methods>("3")
            .unwrap_err()
            .to_string();
        assert!(e.contains("key `methods`"), "{e}");
    }

    /// A name twice in the table is refused, naming it.
    #[test]
    fn a_name_twice_is_refused() {
        let entry = serde_json::to_string(table().get("g").unwrap()).unwrap();
        let text = format!("{{\"g\": {entry}, \"g\": {entry}}}");
        let e = serde_json::from_str::<Methods>(&text)
            .unwrap_err()
            .to_string();
        assert!(e.contains("key `methods.g` appears twice"), "{e}");
    }

    /// `check` refuses a twin of a method the table lacks, a chart-dependent fact that
    /// disagrees with its parameterizations, and a control character in a name.
    #[test]
    fn check_refuses_inconsistent_tables() {
        let mut t = table();
        let mut f = t.get("g_kahan").unwrap().clone();
        f.twin_of = Some("nothing".into());
        t.insert("g_kahan", f);
        let e = t.check().unwrap_err();
        assert!(
            e.contains("`methods.g_kahan.twin_of` is \"nothing\""),
            "{e}"
        );
        let mut t = table();
        let mut f = t.get("rk4").unwrap().clone();
        f.lie_group_params.clear();
        t.insert("rk4", f);
        let e = t.check().unwrap_err();
        assert!(e.contains("`methods.rk4.lie_group` is true"), "{e}");
        let mut t = table();
        let mut f = t.get("g").unwrap().clone();
        f.symplectic = false;
        t.insert("g", f);
        let e = t.check().unwrap_err();
        assert!(e.contains("`methods.g.symplectic` is false but"), "{e}");
        let mut t = table();
        t.insert("x\u{1b}[2J", t.get("g").unwrap().clone());
        let e = t.check().unwrap_err();
        assert!(
            e.contains("control character") && !e.contains('\u{1b}'),
            "{e}"
        );
    }

    /// A table of one method, rk4.
    fn rk4_table() -> Methods {
        let mut t = Methods::default();
        let rk4 = MethodInfo::new("rk4", MethodKind::Explicit, 4).with_stages(4);
        t.insert("rk4", MethodFacts::of(&rk4, "quat"));
        t
    }

    /// With a `methods` table, every record's and fit's integrator must have an entry (the
    /// message names the list, the index and the key); without one (a summary written before
    /// the table existed) any name is read; a family named twice is refused.
    #[test]
    fn records_need_an_entry_when_the_table_is_present() {
        use crate::summary::{Env, FitRecord, Record, RunKey};
        let r = Record::new(RunKey::new("a", "b", "so3", "rk4", "body"), "h");
        let mut s = Summary {
            schema: 1,
            git_commit: "c".into(),
            created_utc: "t".into(),
            env: Env::current(1, None),
            records: vec![r.clone()],
            fits: vec![],
            selection: None,
            methods: Some(rk4_table()),
            families: Some(vec!["rigid_body".into()]),
        };
        assert!(s.check().is_ok());
        s.fits.push(FitRecord {
            key: RunKey::new("a", "b", "so3", "mine", "body"),
            metric: "m".into(),
            order: None,
            reason: None,
            points: vec![],
        });
        let e = s.check().unwrap_err();
        assert!(
            e.contains("fits[0]: key `integrator` is \"mine\", which has no entry in `methods`"),
            "{e}"
        );
        s.methods = None;
        assert!(s.check().is_ok());
        s.families = Some(vec!["rigid_body".into(), "rigid_body".into()]);
        let e = s.check().unwrap_err();
        assert!(
            e.contains("key `families[1]`: `rigid_body` appears twice"),
            "{e}"
        );
    }
}
