//! Benchmark functions: the nine of seed 000 Table 1, with their domains and optima.

pub mod cec2005;
pub mod classic;

use std::fmt;

use thiserror::Error;

use crate::problem::{Bounds, BoxProblem};

/// A benchmark function as Table 1 lists it.
#[derive(Debug, Clone, Copy)]
pub struct TestFunction {
    /// Table 1's code: "f1" … "f9".
    pub key: &'static str,
    /// The function's name, e.g. "Shifted Sphere (CEC 2005 F1)".
    pub name: &'static str,
    /// The search interval of every coordinate.
    pub domain: (f64, f64),
    /// Table 1's "theoretical optimum" (for Ackley N.4 at D = 50 the paper's −150 is not a
    /// proven minimum: see `classic::ackley_4`).
    pub optimum: f64,
    /// Whether `optimum` is the function's known minimum (`false` for Ackley N.4, whose
    /// −150 no search reaches at D = 50: the least found is about −144.7).
    pub optimum_known: bool,
    /// Whether Table 1 counts the function as unimodal (`false`: multimodal).
    pub unimodal: bool,
    evaluate: fn(&[f64]) -> f64,
    /// The only dimensions allowed, when the data fix them (F3's rotation matrices).
    fixed_dimension: Option<&'static [usize]>,
    /// The largest dimension the data allow.
    max_dimension: usize,
}

impl TestFunction {
    /// The function's value at `x`.
    pub fn evaluate(&self, x: &[f64]) -> f64 {
        (self.evaluate)(x)
    }

    /// Whether the function is defined at `dimension` (shift vectors and rotation data).
    pub fn check_dimension(&self, dimension: usize) -> Result<(), FunctionError> {
        let allowed = match self.fixed_dimension {
            Some(only) => only.contains(&dimension),
            None => (2..=self.max_dimension).contains(&dimension),
        };
        if allowed {
            Ok(())
        } else {
            Err(FunctionError::Dimension {
                function: self.key,
                dimension,
                allowed: match self.fixed_dimension {
                    Some(only) => {
                        let list: Vec<String> = only.iter().map(|d| d.to_string()).collect();
                        format!(
                            "{} (the dimensions with a published rotation matrix)",
                            list.join(", ")
                        )
                    }
                    None if self.max_dimension == UNLIMITED => "2 or more".to_string(),
                    None => format!("2 to {} (the published shift vectors)", self.max_dimension),
                },
            })
        }
    }
}

impl fmt::Display for TestFunction {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} {}", self.key, self.name)
    }
}

/// A function refused for a problem.
#[derive(Debug, Error, PartialEq)]
pub enum FunctionError {
    /// The function is not defined at the dimension asked for.
    #[error("{function} is defined for dimension {allowed}, not {dimension}")]
    Dimension {
        /// The function's key.
        function: &'static str,
        /// The dimension asked for.
        dimension: usize,
        /// The dimensions allowed, in words.
        allowed: String,
    },
    /// No Table 1 function has this key.
    #[error("unknown function '{0}' (known: f1 … f9)")]
    Unknown(String),
}

const UNLIMITED: usize = usize::MAX;

/// Seed 000 Table 1, in its order.
pub const TABLE_1: [TestFunction; 9] = [
    TestFunction {
        key: "f1",
        name: "Shifted Sphere (CEC 2005 F1)",
        domain: (-100.0, 100.0),
        optimum: -450.0,
        optimum_known: true,
        unimodal: true,
        evaluate: cec2005::shifted_sphere,
        fixed_dimension: None,
        max_dimension: cec2005::MAX_DIMENSION,
    },
    TestFunction {
        key: "f2",
        name: "Shifted Schwefel 1.2 (CEC 2005 F2)",
        domain: (-100.0, 100.0),
        optimum: -450.0,
        optimum_known: true,
        unimodal: true,
        evaluate: cec2005::shifted_schwefel_1_2,
        fixed_dimension: None,
        max_dimension: cec2005::MAX_DIMENSION,
    },
    TestFunction {
        key: "f3",
        name: "Shifted Rotated Elliptic (CEC 2005 F3)",
        domain: (-100.0, 100.0),
        optimum: -450.0,
        optimum_known: true,
        unimodal: true,
        evaluate: cec2005::shifted_rotated_elliptic,
        fixed_dimension: Some(&cec2005::ROTATED_DIMENSIONS),
        max_dimension: 50,
    },
    TestFunction {
        key: "f4",
        name: "Schwefel 2.22",
        domain: (-10.0, 10.0),
        optimum: 0.0,
        optimum_known: true,
        unimodal: true,
        evaluate: classic::schwefel_2_22,
        fixed_dimension: None,
        max_dimension: UNLIMITED,
    },
    TestFunction {
        key: "f5",
        name: "Ackley N.4",
        domain: (-35.0, 35.0),
        optimum: -150.0,
        optimum_known: false,
        unimodal: false,
        evaluate: classic::ackley_4,
        fixed_dimension: None,
        max_dimension: UNLIMITED,
    },
    TestFunction {
        key: "f6",
        name: "Shifted Rosenbrock (CEC 2005 F6)",
        domain: (-100.0, 100.0),
        optimum: 390.0,
        optimum_known: true,
        unimodal: false,
        evaluate: cec2005::shifted_rosenbrock,
        fixed_dimension: None,
        max_dimension: cec2005::MAX_DIMENSION,
    },
    TestFunction {
        key: "f7",
        name: "Levy",
        domain: (-10.0, 10.0),
        optimum: 0.0,
        optimum_known: true,
        unimodal: false,
        evaluate: classic::levy,
        fixed_dimension: None,
        max_dimension: UNLIMITED,
    },
    TestFunction {
        key: "f8",
        name: "Penalized N.1",
        domain: (-50.0, 50.0),
        optimum: 0.0,
        optimum_known: true,
        unimodal: false,
        evaluate: classic::penalized_1,
        fixed_dimension: None,
        max_dimension: UNLIMITED,
    },
    TestFunction {
        key: "f9",
        name: "Penalized N.2",
        domain: (-50.0, 50.0),
        optimum: 0.0,
        optimum_known: true,
        unimodal: false,
        evaluate: classic::penalized_2,
        fixed_dimension: None,
        max_dimension: UNLIMITED,
    },
];

/// A Table 1 function by key ("f1" … "f9").
pub fn by_key(key: &str) -> Result<&'static TestFunction, FunctionError> {
    let wanted = key.trim().to_ascii_lowercase();
    TABLE_1
        .iter()
        .find(|f| f.key == wanted)
        .ok_or_else(|| FunctionError::Unknown(key.to_string()))
}

/// A test function on its domain at a given dimension: an optimizer's problem.
#[derive(Debug, Clone)]
pub struct FunctionProblem {
    function: &'static TestFunction,
    bounds: Bounds,
}

impl FunctionProblem {
    /// `function` on its domain in `dimension` coordinates; errs when the function is not
    /// defined at that dimension.
    pub fn new(function: &'static TestFunction, dimension: usize) -> Result<Self, FunctionError> {
        function.check_dimension(dimension)?;
        let (low, high) = function.domain;
        let bounds = Bounds::cube(dimension, low, high).expect("Table 1 domains are valid boxes");
        Ok(Self { function, bounds })
    }

    /// The test function.
    pub fn function(&self) -> &'static TestFunction {
        self.function
    }
}

impl BoxProblem for FunctionProblem {
    fn bounds(&self) -> &Bounds {
        &self.bounds
    }

    fn evaluate(&self, x: &[f64]) -> f64 {
        self.function.evaluate(x)
    }
}
