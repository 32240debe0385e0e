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

/// A method by its name, or the midpoint rule where the argument is not given.
#[allow(dead_code)]
pub fn method(arg: Option<String>) -> anyhow::Result<rope::methods::MethodKind> {
    use rope::methods::MethodKind;
    let name = arg.unwrap_or_else(|| MethodKind::Midpoint.name().into());
    MethodKind::ALL
        .into_iter()
        .find(|m| m.name() == name)
        .ok_or_else(|| {
            let names: Vec<&str> = MethodKind::ALL.iter().map(|m| m.name()).collect();
            anyhow::anyhow!("METHOD {name:?}: one of {}", names.join(", "))
        })
}
