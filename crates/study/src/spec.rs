//! The study spec (TOML) and its expansion into the points of the sweep.
//!
//! ```toml
//! name = "hertz"                 # names the output files
//! scene = "hertz"                # a built-in scene
//! reference = "analytic"         # or "finest": the finest run of the first method
//! tolerance = 0.05               # relative error above which a converged run is wrong
//! accuracy_target = 0.02         # "equal accuracy" for the summary's fastest method
//! repeat = 1                     # runs per point; the fastest time is kept
//!
//! [scene_params]                 # fixed parameters of the scene
//! load = 100.0
//!
//! [sweep]
//! refine = [1, 2, 4, 8]          # mesh refinement levels
//! stiffness_ratio = [1.0]
//! steps = [1]                    # number of load steps
//! coulomb = [0.0]                # friction coefficients μ (frictional scenes)
//!
//! [[methods]]
//! kind = "discrete-contrainte"
//!
//! [[methods]]
//! kind = "discrete-penalisation"
//! coefficients = [1e2, 1e4, 1e6, 1e8, 1e10]
//! ```

use crate::error::StudyError;
use crate::method::{short_number, Method, MethodFamily};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// What errors are measured against.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Reference {
    /// The scene's analytic value ([`crate::Measures::reference`]).
    Analytic,
    /// The converged run of the first method on the finest mesh, for the
    /// same stiffness ratio and number of steps.
    Finest,
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSpec {
    name: String,
    scene: String,
    reference: Reference,
    #[serde(default = "default_tolerance")]
    tolerance: f64,
    #[serde(default = "default_target")]
    accuracy_target: f64,
    #[serde(default = "default_repeat")]
    repeat: u32,
    #[serde(default)]
    scene_params: BTreeMap<String, f64>,
    sweep: RawSweep,
    methods: Vec<RawMethod>,
}

fn default_tolerance() -> f64 {
    0.1
}
fn default_target() -> f64 {
    0.02
}
fn default_repeat() -> u32 {
    1
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSweep {
    refine: Vec<u32>,
    #[serde(default = "one_f64")]
    stiffness_ratio: Vec<f64>,
    #[serde(default = "one_u32")]
    steps: Vec<u32>,
    /// Friction coefficients μ (`COULOMB`); only frictional methods use it.
    #[serde(default = "zero_f64")]
    coulomb: Vec<f64>,
}

fn zero_f64() -> Vec<f64> {
    vec![0.0]
}

fn one_f64() -> Vec<f64> {
    vec![1.0]
}
fn one_u32() -> Vec<u32> {
    vec![1]
}

#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMethod {
    kind: MethodFamily,
    #[serde(default)]
    coefficients: Vec<f64>,
}

/// A validated study.
#[derive(Clone, Debug, PartialEq)]
pub struct StudySpec {
    pub name: String,
    pub scene: String,
    pub reference: Reference,
    /// Relative error above which a converged run counts as wrong.
    pub tolerance: f64,
    /// The accuracy at which the summary compares times.
    pub accuracy_target: f64,
    pub repeat: u32,
    pub scene_params: BTreeMap<String, f64>,
    /// Methods in spec order; the first one is the reference of `finest`.
    pub methods: Vec<Method>,
    pub refine: Vec<u32>,
    pub stiffness_ratio: Vec<f64>,
    pub steps: Vec<u32>,
    /// Friction coefficients μ swept (`[0.0]` for frictionless studies).
    pub coulomb: Vec<f64>,
}

/// The physical setting of a run apart from its method and mesh: what a
/// reference, a convergence series and a row of the stability map share.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Setting {
    /// Stiffness of the second body over the first one's.
    pub stiffness_ratio: f64,
    /// Number of load steps.
    pub steps: u32,
    /// Friction coefficient μ (`COULOMB`), 0 without friction.
    pub coulomb: f64,
}

impl Setting {
    /// A short label naming only what the study sweeps (`ratio 1e3, 4
    /// steps, μ 0.3`), or `all` when it sweeps none of them.
    pub fn label(&self, spec: &StudySpec) -> String {
        let mut parts = Vec::new();
        if spec.stiffness_ratio.len() > 1 {
            parts.push(format!("ratio {}", short_number(self.stiffness_ratio)));
        }
        if spec.steps.len() > 1 {
            parts.push(format!("{} steps", self.steps));
        }
        if spec.coulomb.len() > 1 {
            parts.push(format!("μ {}", short_number(self.coulomb)));
        }
        if parts.is_empty() {
            "all".into()
        } else {
            parts.join(", ")
        }
    }

    /// Every field, for tables: `ratio 1, 1 steps, μ 0`.
    pub fn full_label(&self) -> String {
        format!(
            "ratio {}, {} steps, μ {}",
            short_number(self.stiffness_ratio),
            self.steps,
            short_number(self.coulomb)
        )
    }
}

/// One run of the sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Point {
    /// Position in the sweep (0-based), the CSV's `run` column.
    pub index: usize,
    pub method: Method,
    /// Mesh refinement level (the scene says what it means: elements per
    /// side, or per contact half-width).
    pub refine: u32,
    /// Stiffness of the second body over the first one's.
    pub stiffness_ratio: f64,
    /// Number of load steps.
    pub steps: u32,
    /// Friction coefficient μ (`COULOMB`).
    pub coulomb: f64,
}

impl Point {
    pub fn setting(&self) -> Setting {
        Setting {
            stiffness_ratio: self.stiffness_ratio,
            steps: self.steps,
            coulomb: self.coulomb,
        }
    }
}

impl StudySpec {
    /// Reads and validates a spec file.
    pub fn from_file(path: &Path) -> Result<StudySpec, StudyError> {
        let text = std::fs::read_to_string(path).map_err(|e| StudyError::Read {
            path: path.to_path_buf(),
            message: e.to_string(),
        })?;
        StudySpec::from_toml(&text).map_err(|message| StudyError::Spec {
            path: path.to_path_buf(),
            message,
        })
    }

    /// Parses and validates a spec; the message says what is wrong and where.
    pub fn from_toml(text: &str) -> Result<StudySpec, String> {
        let raw: RawSpec = toml::from_str(text).map_err(|e| e.to_string())?;
        if raw.name.is_empty()
            || !raw
                .name
                .chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
        {
            return Err(format!(
                "name `{}` must be a non-empty file stem of letters, digits, `-` and `_`",
                raw.name
            ));
        }
        if !(raw.tolerance > 0.0 && raw.accuracy_target > 0.0) {
            return Err("tolerance and accuracy_target must be positive".into());
        }
        if raw.repeat == 0 {
            return Err("repeat must be at least 1".into());
        }
        if raw.methods.is_empty() {
            return Err("no [[methods]]: give at least one".into());
        }
        if raw.sweep.refine.is_empty() || raw.sweep.refine.contains(&0) {
            return Err("sweep.refine must list refinement levels ≥ 1".into());
        }
        if raw.sweep.stiffness_ratio.is_empty()
            || raw
                .sweep
                .stiffness_ratio
                .iter()
                .any(|r| !(r.is_finite() && *r > 0.0))
        {
            return Err("sweep.stiffness_ratio must list positive numbers".into());
        }
        if raw.sweep.steps.is_empty() || raw.sweep.steps.contains(&0) {
            return Err("sweep.steps must list step counts ≥ 1".into());
        }
        if raw.sweep.coulomb.is_empty()
            || raw
                .sweep
                .coulomb
                .iter()
                .any(|m| !(m.is_finite() && *m >= 0.0))
        {
            return Err("sweep.coulomb must list friction coefficients ≥ 0".into());
        }
        let mut methods = Vec::new();
        for (i, m) in raw.methods.iter().enumerate() {
            let coefs: Vec<Option<f64>> = if m.coefficients.is_empty() {
                vec![None]
            } else {
                m.coefficients.iter().copied().map(Some).collect()
            };
            for c in coefs {
                let method = Method::new(m.kind, c).map_err(|e| format!("methods[{i}]: {e}"))?;
                if methods.contains(&method) {
                    return Err(format!("methods[{i}]: {} is listed twice", method.label()));
                }
                methods.push(method);
            }
        }
        let frictional = methods
            .iter()
            .filter(|m| m.family().is_frictional())
            .count();
        if frictional > 0 && frictional < methods.len() {
            return Err(
                "methods mix frictional (`*-friction-*`) and frictionless kinds: a study compares \
                 one or the other"
                    .into(),
            );
        }
        if frictional > 0 && raw.sweep.coulomb.contains(&0.0) {
            return Err(
                "sweep.coulomb: frictional methods need friction coefficients μ > 0".into(),
            );
        }
        if frictional == 0 && raw.sweep.coulomb.iter().any(|&m| m != 0.0) {
            return Err(
                "sweep.coulomb is for frictional methods (`*-friction-*` kinds); these methods \
                 are frictionless"
                    .into(),
            );
        }
        Ok(StudySpec {
            name: raw.name,
            scene: raw.scene,
            reference: raw.reference,
            tolerance: raw.tolerance,
            accuracy_target: raw.accuracy_target,
            repeat: raw.repeat,
            scene_params: raw.scene_params,
            methods,
            refine: raw.sweep.refine,
            stiffness_ratio: raw.sweep.stiffness_ratio,
            steps: raw.sweep.steps,
            coulomb: raw.sweep.coulomb,
        })
    }

    /// Every setting of the sweep: stiffness ratio × steps × μ, in the
    /// order of the spec's lists.
    pub fn settings(&self) -> Vec<Setting> {
        let mut out = Vec::new();
        for &stiffness_ratio in &self.stiffness_ratio {
            for &steps in &self.steps {
                for &coulomb in &self.coulomb {
                    out.push(Setting {
                        stiffness_ratio,
                        steps,
                        coulomb,
                    });
                }
            }
        }
        out
    }

    /// Every point of the sweep: methods × refine × settings, coarse
    /// meshes first so that a study interrupted early has every method.
    pub fn points(&self) -> Vec<Point> {
        let mut points = Vec::new();
        let settings = self.settings();
        for &refine in &self.refine {
            for s in &settings {
                for &method in &self.methods {
                    points.push(Point {
                        index: points.len(),
                        method,
                        refine,
                        stiffness_ratio: s.stiffness_ratio,
                        steps: s.steps,
                        coulomb: s.coulomb,
                    });
                }
            }
        }
        points
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SPEC: &str = r#"
name = "t"
scene = "fake"
reference = "finest"
[sweep]
refine = [1, 2]
stiffness_ratio = [1.0, 1e3]
[[methods]]
kind = "discrete-contrainte"
[[methods]]
kind = "discrete-penalisation"
coefficients = [1e3, 1e6]
"#;

    #[test]
    fn expands_methods_times_parameters() {
        let spec = StudySpec::from_toml(SPEC).unwrap();
        assert_eq!(spec.methods.len(), 3);
        assert_eq!(spec.steps, vec![1]);
        let points = spec.points();
        assert_eq!(points.len(), 3 * 2 * 2);
        assert!(points.iter().enumerate().all(|(i, p)| p.index == i));
        assert_eq!(points[0].refine, 1);
        assert_eq!(points[11].refine, 2);
    }

    #[test]
    fn unknown_keys_and_kinds_are_reported_with_their_place() {
        let e = StudySpec::from_toml(&SPEC.replace("refine", "refin")).unwrap_err();
        assert!(e.contains("refin"), "{e}");
        let e = StudySpec::from_toml(&SPEC.replace("discrete-contrainte", "discrete-contact"))
            .unwrap_err();
        assert!(e.contains("discrete-contact") && e.contains("line"), "{e}");
    }

    #[test]
    fn friction_coefficients_are_a_sweep_axis_of_frictional_studies() {
        let text = r#"
name = "f"
scene = "friction"
reference = "analytic"
[sweep]
refine = [2]
steps = [1, 4]
coulomb = [0.1, 0.3]
[[methods]]
kind = "discrete-friction-penalisation"
coefficients = [1e5, 1e7]
[[methods]]
kind = "continuous-friction-standard"
"#;
        let spec = StudySpec::from_toml(text).unwrap();
        assert_eq!(spec.methods.len(), 3);
        assert_eq!(spec.methods[2].coefficient(), Some(100.0));
        assert_eq!(spec.settings().len(), 4);
        let points = spec.points();
        assert_eq!(points.len(), 3 * 4);
        assert_eq!(points[3].coulomb, 0.3);
        assert_eq!(points[3].setting().label(&spec), "1 steps, μ 0.3");
        let e = StudySpec::from_toml(&text.replace("[0.1, 0.3]", "[0.0, 0.3]")).unwrap_err();
        assert!(e.contains("μ > 0"), "{e}");
        let e = StudySpec::from_toml(&format!(
            "{text}[[methods]]\nkind = \"discrete-contrainte\"\n"
        ))
        .unwrap_err();
        assert!(e.contains("mix"), "{e}");
        let e =
            StudySpec::from_toml(&SPEC.replace("[sweep]", "[sweep]\ncoulomb = [0.2]")).unwrap_err();
        assert!(e.contains("frictionless"), "{e}");
        let e = StudySpec::from_toml(&text.replace("[0.1, 0.3]", "[-1.0]")).unwrap_err();
        assert!(e.contains("≥ 0"), "{e}");
    }

    #[test]
    fn missing_penalty_coefficient_is_an_error() {
        let text = SPEC.replace("coefficients = [1e3, 1e6]", "");
        let e = StudySpec::from_toml(&text).unwrap_err();
        assert!(e.contains("methods[1]") && e.contains("E_N"), "{e}");
    }
}
