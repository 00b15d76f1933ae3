//! Operations on TOML value trees that settings files and sequence scripts need: overlaying a
//! partial table on complete settings (unknown keys are errors), interpolating two complete
//! settings trees leaf by leaf.

use toml::{Table, Value};

/// `base` with every key of `partial` replaced. Tables merge recursively, except texture
/// tables (they carry `kind`) and arrays, which are replaced whole. A key that `base` lacks
/// is an error `(field path, message)`; an integer over a float becomes a float.
pub fn merge(base: &Table, partial: &Table, prefix: &str) -> Result<Table, (String, String)> {
    let mut out = base.clone();
    for (key, value) in partial {
        let path = join(prefix, key);
        let Some(old) = base.get(key) else {
            let message = if prefix == "objects" {
                let names: Vec<&str> = base.keys().map(String::as_str).collect();
                format!(
                    "unknown object '{key}' (the data file's objects: {})",
                    names.join(", ")
                )
            } else {
                let known: Vec<&str> = base.keys().map(String::as_str).collect();
                format!(
                    "unknown field '{key}' (expected one of: {})",
                    known.join(", ")
                )
            };
            return Err((path, message));
        };
        let new = match (old, value) {
            (Value::Table(o), Value::Table(p)) if !p.contains_key("kind") => {
                Value::Table(merge(o, p, &path)?)
            }
            (Value::Float(_), Value::Integer(i)) => Value::Float(*i as f64),
            _ => value.clone(),
        };
        out.insert(key.clone(), new);
    }
    Ok(out)
}

fn join(prefix: &str, key: &str) -> String {
    if prefix.is_empty() {
        key.to_string()
    } else {
        format!("{prefix}.{key}")
    }
}

/// Interpolates two trees of the same shape at fraction `s` ∈ [0, 1]: floats linearly
/// (`a + s·(b − a)`), everything else (integers, strings, booleans, arrays of other lengths)
/// held at `a` until `s` reaches 1, then `b`.
pub fn lerp(a: &Value, b: &Value, s: f64) -> Value {
    match (a, b) {
        (Value::Float(x), Value::Float(y)) => Value::Float(mix(*x, *y, s)),
        (Value::Float(x), Value::Integer(y)) => Value::Float(mix(*x, *y as f64, s)),
        (Value::Integer(x), Value::Float(y)) => Value::Float(mix(*x as f64, *y, s)),
        (Value::Table(x), Value::Table(y))
            if x.get("kind") == y.get("kind") && x.len() == y.len() =>
        {
            let mut out = Table::new();
            for (k, va) in x {
                let v = match y.get(k) {
                    Some(vb) => lerp(va, vb, s),
                    None => hold(va, va, s),
                };
                out.insert(k.clone(), v);
            }
            Value::Table(out)
        }
        (Value::Array(x), Value::Array(y)) if x.len() == y.len() => {
            Value::Array(x.iter().zip(y).map(|(p, q)| lerp(p, q, s)).collect())
        }
        _ => hold(a, b, s),
    }
}

/// `x + s·(y − x)`, exactly x at s = 0 (a keyframe's own value, −0.0 included); where
/// y − x overflows (finite values of opposite sign near the largest float), the same point
/// as `(1 − s)·x + s·y`, kept between x and y.
fn mix(x: f64, y: f64, s: f64) -> f64 {
    if s == 0.0 {
        return x;
    }
    let v = x + s * (y - x);
    if v.is_finite() || !(x.is_finite() && y.is_finite()) {
        v
    } else {
        (x * (1.0 - s) + y * s).clamp(x.min(y), x.max(y))
    }
}

fn hold(a: &Value, b: &Value, s: f64) -> Value {
    if s >= 1.0 {
        b.clone()
    } else {
        a.clone()
    }
}
