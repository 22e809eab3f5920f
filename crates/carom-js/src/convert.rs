//! Values across the boundary: JavaScript objects read field by field with a clear error for
//! anything that is not what the type says, and plain objects written back.

use carom::{Real, Vec2};
use js_sys::{Array, Object, Reflect};
use wasm_bindgen::prelude::*;

#[wasm_bindgen(inline_js = "export function vec2(x, y) { return { x, y }; }")]
extern "C" {
    /// A plain `{ x, y }`, made in one call.
    #[wasm_bindgen(js_name = vec2)]
    fn plain_vec2(x: f64, y: f64) -> JsValue;
}

/// `v` as a plain `{ x, y }`.
pub(crate) fn vec2_out(v: Vec2) -> JsValue {
    plain_vec2(v.x as f64, v.y as f64)
}

/// An error whose message names where in the input it was.
pub(crate) fn error(what: &str, problem: impl std::fmt::Display) -> JsError {
    JsError::new(&format!("{what}: {problem}"))
}

/// How a JavaScript value reads in an error message.
fn describe(value: &JsValue) -> String {
    if value.is_undefined() {
        "undefined".into()
    } else if value.is_null() {
        "null".into()
    } else if let Some(s) = value.as_string() {
        format!("the string {s:?}")
    } else if let Some(n) = value.as_f64() {
        format!("{n}")
    } else if value.is_bigint() {
        "a bigint".into()
    } else if Array::is_array(value) {
        "an array".into()
    } else if value.is_function() {
        "a function".into()
    } else if value.is_object() {
        "an object".into()
    } else {
        format!("{value:?}")
    }
}

/// A finite number, as carom's `Real`.
pub(crate) fn real(value: &JsValue, what: &str) -> Result<Real, JsError> {
    match value.as_f64() {
        Some(n) if n.is_finite() => Ok(n as Real),
        _ => Err(error(
            what,
            format!("expected a finite number, got {}", describe(value)),
        )),
    }
}

/// A checked finite `f64` argument (numbers passed directly arrive as `f64`).
pub(crate) fn finite(n: f64, what: &str) -> Result<Real, JsError> {
    if n.is_finite() {
        Ok(n as Real)
    } else {
        Err(error(what, format!("expected a finite number, got {n}")))
    }
}

/// A point or vector `{ x, y }` of finite numbers.
pub(crate) fn vec2(value: &JsValue, what: &str) -> Result<Vec2, JsError> {
    if !value.is_object() || Array::is_array(value) {
        return Err(error(
            what,
            format!("expected a vector {{ x, y }}, got {}", describe(value)),
        ));
    }
    let x = get(value, "x");
    let y = get(value, "y");
    Ok(Vec2::new(
        real(&x, &format!("{what}.x"))?,
        real(&y, &format!("{what}.y"))?,
    ))
}

/// A field, `undefined` when absent (or when reading it throws, which the caller then
/// reports as the wrong type).
fn get(object: &JsValue, key: &str) -> JsValue {
    Reflect::get(object, &JsValue::from_str(key)).unwrap_or(JsValue::UNDEFINED)
}

/// An options object read field by field. Fields it does not know are an error, so a typo
/// (`desnity`) is caught where it is made instead of silently taking the default.
pub(crate) struct Fields {
    object: JsValue,
    what: String,
}

impl Fields {
    /// `value` as an object of the fields `known` at most; `undefined` reads as `{}` when
    /// `optional`.
    pub(crate) fn new(
        value: &JsValue,
        what: &str,
        known: &[&str],
        optional: bool,
    ) -> Result<Fields, JsError> {
        let object = if optional && value.is_undefined() {
            Object::new().into()
        } else {
            value.clone()
        };
        if !object.is_object() || Array::is_array(&object) || object.is_function() {
            return Err(error(
                what,
                format!("expected an object, got {}", describe(value)),
            ));
        }
        for key in Object::keys(object.unchecked_ref::<Object>()).iter() {
            let key = key.as_string().unwrap_or_default();
            if !known.contains(&key.as_str()) {
                return Err(error(
                    what,
                    format!("unknown field `{key}` (known: {})", known.join(", ")),
                ));
            }
        }
        Ok(Fields {
            object,
            what: what.to_string(),
        })
    }

    /// The path of a field, for messages.
    pub(crate) fn path(&self, key: &str) -> String {
        format!("{}.{key}", self.what)
    }

    /// A field's value, `None` when it is absent or `undefined`.
    pub(crate) fn value(&self, key: &str) -> Option<JsValue> {
        let value = get(&self.object, key);
        (!value.is_undefined()).then_some(value)
    }

    /// A field that must be there.
    pub(crate) fn required(&self, key: &str) -> Result<JsValue, JsError> {
        self.value(key)
            .ok_or_else(|| error(&self.path(key), "missing"))
    }

    pub(crate) fn real(&self, key: &str) -> Result<Option<Real>, JsError> {
        self.value(key)
            .map(|v| real(&v, &self.path(key)))
            .transpose()
    }

    pub(crate) fn required_real(&self, key: &str) -> Result<Real, JsError> {
        real(&self.required(key)?, &self.path(key))
    }

    pub(crate) fn vec2(&self, key: &str) -> Result<Option<Vec2>, JsError> {
        self.value(key)
            .map(|v| vec2(&v, &self.path(key)))
            .transpose()
    }

    pub(crate) fn required_vec2(&self, key: &str) -> Result<Vec2, JsError> {
        vec2(&self.required(key)?, &self.path(key))
    }

    pub(crate) fn bool(&self, key: &str) -> Result<Option<bool>, JsError> {
        self.value(key)
            .map(|v| {
                v.as_bool().ok_or_else(|| {
                    error(
                        &self.path(key),
                        format!("expected true or false, got {}", describe(&v)),
                    )
                })
            })
            .transpose()
    }

    pub(crate) fn string(&self, key: &str) -> Result<Option<String>, JsError> {
        self.value(key)
            .map(|v| {
                v.as_string().ok_or_else(|| {
                    error(
                        &self.path(key),
                        format!("expected a string, got {}", describe(&v)),
                    )
                })
            })
            .transpose()
    }

    /// A whole number in `[0, 2^64)`: a number up to 2^53, or a bigint.
    pub(crate) fn bits(&self, key: &str) -> Result<Option<u64>, JsError> {
        self.value(key)
            .map(|v| bits(&v, &self.path(key)))
            .transpose()
    }

    /// A whole number that fits an `i32`.
    pub(crate) fn int(&self, key: &str) -> Result<Option<i32>, JsError> {
        self.value(key)
            .map(|v| match v.as_f64() {
                Some(n) if n.fract() == 0.0 && n >= i32::MIN as f64 && n <= i32::MAX as f64 => {
                    Ok(n as i32)
                }
                _ => Err(error(
                    &self.path(key),
                    format!("expected a whole number of 32 bits, got {}", describe(&v)),
                )),
            })
            .transpose()
    }

    /// An array's items.
    pub(crate) fn array(&self, key: &str) -> Result<Option<Vec<JsValue>>, JsError> {
        self.value(key)
            .map(|v| array(&v, &self.path(key)))
            .transpose()
    }
}

/// One string field of an object, read before its other fields are checked.
pub(crate) fn string_field(
    value: &JsValue,
    key: &str,
    what: &str,
) -> Result<Option<String>, JsError> {
    if !value.is_object() || Array::is_array(value) || value.is_function() {
        return Err(error(
            what,
            format!("expected an object, got {}", describe(value)),
        ));
    }
    let field = get(value, key);
    if field.is_undefined() {
        return Ok(None);
    }
    field.as_string().map(Some).ok_or_else(|| {
        error(
            &format!("{what}.{key}"),
            format!("expected a string, got {}", describe(&field)),
        )
    })
}

/// An array's items.
pub(crate) fn array(value: &JsValue, what: &str) -> Result<Vec<JsValue>, JsError> {
    if !Array::is_array(value) {
        return Err(error(
            what,
            format!("expected an array, got {}", describe(value)),
        ));
    }
    Ok(Array::from(value).iter().collect())
}

/// A whole number in `[0, 2^64)`: a number up to 2^53 or a bigint.
pub(crate) fn bits(value: &JsValue, what: &str) -> Result<u64, JsError> {
    const EXACT: f64 = 9_007_199_254_740_992.0; // 2^53
    if let Some(n) = value.as_f64() {
        if n.fract() == 0.0 && (0.0..=EXACT).contains(&n) {
            return Ok(n as u64);
        }
    } else if value.is_bigint()
        && let Ok(n) = u64::try_from(value.clone())
    {
        return Ok(n);
    }
    Err(error(
        what,
        format!(
            "expected a whole number from 0 to 2^53 or a bigint below 2^64, got {}",
            describe(value)
        ),
    ))
}

/// A JavaScript array of `items`.
pub(crate) fn array_of<T: Into<JsValue>>(items: impl IntoIterator<Item = T>) -> Array {
    items.into_iter().map(Into::into).collect()
}

/// A plain object of `fields`, in order.
pub(crate) fn object(fields: &[(&str, JsValue)]) -> JsValue {
    let object = Object::new();
    for (key, value) in fields {
        // Setting a field on a fresh plain object does not fail.
        let _ = Reflect::set(&object, &JsValue::from_str(key), value);
    }
    object.into()
}
