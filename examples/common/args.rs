//! What the examples read from their command line: numbers, each argument with its default.

/// A comma-separated list of numbers, or `default` where the argument is not given.
#[allow(dead_code)]
pub fn numbers(arg: Option<String>, default: &[f64]) -> anyhow::Result<Vec<f64>> {
    match arg {
        None => Ok(default.to_vec()),
        Some(text) => text
            .split(',')
            .map(|v| v.trim().parse().map_err(|e| anyhow::anyhow!("{v:?}: {e}")))
            .collect(),
    }
}

/// One number, or `default` where the argument is not given.
#[allow(dead_code)]
pub fn number(arg: Option<String>, default: f64) -> anyhow::Result<f64> {
    match arg {
        None => Ok(default),
        Some(text) => text.parse().map_err(|e| anyhow::anyhow!("{text:?}: {e}")),
    }
}
