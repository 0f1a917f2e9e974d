//! The scene trait and the registry of built-in scenes.

use crate::error::StudyError;
use crate::outcome::{Failure, Measures};
use crate::scenes;
use crate::spec::Point;
use std::collections::BTreeMap;

/// A problem a study can run at any point of its sweep.
///
/// `run` must not panic on any point (the engine catches panics anyway and
/// records them as failures); a run that fails or converges to a wrong
/// answer returns a [`Failure`] with its reason.
pub trait Scene {
    /// The compared quantity, with its unit, e.g. `peak pressure p0 (MPa)`.
    fn quantity(&self) -> String;
    /// One line describing the scene for the summary.
    fn describe(&self) -> String;
    fn run(&self, point: &Point) -> Result<Measures, Failure>;
}

/// Names of the built-in scenes.
pub const BUILTIN: [&str; 4] = ["zzzz237", "hertz", "friction", "fake"];

/// Builds a built-in scene from its name and fixed parameters.
pub fn builtin_scene(
    name: &str,
    params: &BTreeMap<String, f64>,
) -> Result<Box<dyn Scene>, StudyError> {
    match name {
        "fake" => Ok(Box::new(scenes::fake::FakeScene::from_params(params)?)),
        "zzzz237" => Ok(Box::new(scenes::zzzz237::TwoBlocks::from_params(params)?)),
        "hertz" => Ok(Box::new(scenes::hertz::Hertz::from_params(params)?)),
        "friction" => Ok(Box::new(scenes::friction::Friction::from_params(params)?)),
        _ => Err(StudyError::UnknownScene {
            name: name.to_string(),
            known: BUILTIN.to_vec(),
            suggestion: BUILTIN
                .iter()
                .map(|k| (strsim::levenshtein(name, k), *k))
                .filter(|(d, _)| *d <= 3)
                .min()
                .map(|(_, k)| k.to_string()),
        }),
    }
}

/// Takes the known parameters out of a scene's table, refusing unknown ones
/// (with a did-you-mean) so that a typo does not silently change a study.
pub struct Params<'a> {
    scene: &'static str,
    table: &'a BTreeMap<String, f64>,
    known: &'static [&'static str],
}

impl<'a> Params<'a> {
    pub fn new(
        scene: &'static str,
        table: &'a BTreeMap<String, f64>,
        known: &'static [&'static str],
    ) -> Result<Params<'a>, StudyError> {
        for key in table.keys() {
            if !known.contains(&key.as_str()) {
                let hint = known
                    .iter()
                    .map(|k| (strsim::levenshtein(key, k), *k))
                    .filter(|(d, _)| *d <= 3)
                    .min()
                    .map(|(_, k)| format!(" (did you mean `{k}`?)"))
                    .unwrap_or_default();
                return Err(StudyError::SceneParam(format!(
                    "scene `{scene}` has no parameter `{key}`{hint}; its parameters: {}",
                    known.join(", ")
                )));
            }
        }
        Ok(Params {
            scene,
            table,
            known,
        })
    }

    /// A positive parameter, or its default.
    pub fn positive(&self, key: &str, default: f64) -> Result<f64, StudyError> {
        debug_assert!(self.known.contains(&key));
        let v = self.table.get(key).copied().unwrap_or(default);
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(StudyError::SceneParam(format!(
                "scene `{}`: `{key}` = {v} must be a positive number",
                self.scene
            )))
        }
    }

    /// A parameter in `[lo, hi)`, or its default.
    pub fn within(&self, key: &str, default: f64, lo: f64, hi: f64) -> Result<f64, StudyError> {
        let v = self.table.get(key).copied().unwrap_or(default);
        if v >= lo && v < hi {
            Ok(v)
        } else {
            Err(StudyError::SceneParam(format!(
                "scene `{}`: `{key}` = {v} must lie in [{lo}, {hi})",
                self.scene
            )))
        }
    }
}
