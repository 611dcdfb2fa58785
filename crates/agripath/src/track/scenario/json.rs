//! Reading the JSON scenario files: values at dotted paths, numbers, points and threat rows
//! checked as they are read, and every key accounted for (used, documentation, or refused).

use serde_json::Value;

use super::Threat;
use crate::error::{Fault, InputError};

/// Why an embedded or read scenario failed: a fault in the file, or another file's error.
pub(super) enum Loaded {
    Fault(Fault),
    Input(InputError),
}

impl From<Fault> for Loaded {
    fn from(fault: Fault) -> Self {
        Loaded::Fault(fault)
    }
}

pub(super) fn embedded(text: &str) -> Value {
    serde_json::from_str(text).expect("embedded scenario is valid JSON")
}

/// The value at a dotted path.
pub(super) fn lookup<'a>(value: &'a Value, path: &str) -> Result<&'a Value, Fault> {
    path.split('.').try_fold(value, |inner, key| {
        inner
            .get(key)
            .ok_or_else(|| Fault::Structure(format!("missing key '{path}'")))
    })
}

pub(super) fn text(value: &Value, path: &str) -> Result<String, Fault> {
    lookup(value, path)?
        .as_str()
        .map(str::to_owned)
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be a string")))
}

pub(super) fn number(value: &Value, path: &str) -> Result<f64, Fault> {
    let number = lookup(value, path)?
        .as_f64()
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be a number")))?;
    if number.is_finite() {
        Ok(number)
    } else {
        Err(Fault::NonFinite)
    }
}

pub(super) fn numbers(value: &Value, path: &str) -> Result<Vec<f64>, Fault> {
    let array = lookup(value, path)?
        .as_array()
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be an array of numbers")))?;
    array
        .iter()
        .map(|item| {
            item.as_f64()
                .filter(|number| number.is_finite())
                .ok_or_else(|| Fault::Structure(format!("'{path}' must hold finite numbers")))
        })
        .collect()
}

pub(super) fn point(value: &Value, path: &str) -> Result<[f64; 3], Fault> {
    let values = numbers(value, path)?;
    <[f64; 3]>::try_from(values.as_slice())
        .map_err(|_| Fault::Structure(format!("'{path}' must be [x, y, z]")))
}

pub(super) fn threats(rows: &Value, path: &str, width: usize) -> Result<Vec<Threat>, Fault> {
    let rows = rows
        .as_array()
        .ok_or_else(|| Fault::Structure(format!("'{path}' must be an array of cylinders")))?;
    rows.iter()
        .enumerate()
        .map(|(index, row)| {
            let values: Option<Vec<f64>> = row
                .as_array()
                .map(|items| items.iter().filter_map(Value::as_f64).collect());
            match values {
                Some(values) if values.len() == width && values.iter().all(|v| v.is_finite()) => {
                    let radius = values[width - 1];
                    if radius <= 0.0 {
                        return Err(Fault::InvalidValue {
                            what: format!("{path}[{index}] radius"),
                            value: radius.to_string(),
                            why: "a threat cylinder needs a positive radius".into(),
                        });
                    }
                    Ok(Threat {
                        x: values[0],
                        y: values[1],
                        radius,
                    })
                }
                _ => Err(Fault::Structure(format!(
                    "'{path}[{index}]' must hold {width} finite numbers"
                ))),
            }
        })
        .collect()
}

/// Refuses any key of the object at `path` that is not in `known` (`path` "" for the top).
pub(super) fn only_keys(value: &Value, path: &str, known: &[&str]) -> Result<(), Fault> {
    let Some(object) = value.as_object() else {
        return Err(Fault::Structure(format!(
            "'{}' must be an object",
            if path.is_empty() {
                "the scenario"
            } else {
                path
            }
        )));
    };
    match object.keys().find(|key| !known.contains(&key.as_str())) {
        None => Ok(()),
        Some(key) => {
            let full = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            Err(Fault::Structure(format!(
                "unknown key '{full}' (known here: {})",
                known.join(", ")
            )))
        }
    }
}

/// A paper's algorithm setting given in a scenario must be the one the planner runs.
pub(super) fn expect_setting(value: &Value, path: &str, expected: f64) -> Result<(), Fault> {
    if lookup(value, path).is_err() {
        return Ok(());
    }
    let given = number(value, path)?;
    if (given - expected).abs() <= 1e-9 * expected.abs().max(1.0) {
        Ok(())
    } else {
        Err(Fault::InvalidValue {
            what: path.into(),
            value: given.to_string(),
            why: format!(
                "the planner runs the paper's {expected}; algorithm settings are not scenario settings"
            ),
        })
    }
}

/// A whole number in `least..=most`, the bounds the scenario's checks will hold it to (a
/// message that says 0..=N and then refuses 0 sends the reader round twice).
pub(super) fn count(value: &Value, path: &str, least: f64, most: f64) -> Result<usize, Fault> {
    let given = number(value, path)?;
    if given.fract() == 0.0 && (least..=most).contains(&given) {
        Ok(given as usize)
    } else {
        Err(Fault::InvalidValue {
            what: path.into(),
            value: given.to_string(),
            why: format!("must be a whole number in {least}..={most}"),
        })
    }
}

/// A task's point: its own `key`, else the scenario's top-level one.
pub(super) fn task_point(scenario: &Value, task: &Value, key: &str) -> Result<[f64; 3], Fault> {
    if task.get(key).is_some() {
        point(task, key)
    } else if scenario.get(key).is_some() {
        point(scenario, key)
    } else {
        Err(Fault::Structure(format!(
            "missing key '{key}' (in the task or at the top level)"
        )))
    }
}

/// Keys of the papers' own figures and notes, kept beside the data (decision 0013).
pub(super) const DOCUMENTATION: [&str; 5] = [
    "source",
    "note",
    "threat_note",
    "reference",
    "field_experiment",
];
