//! Serde for numbers that may be infinite (row sides, activity bounds): finite values as JSON
//! numbers, `±∞` as the strings `"inf"` / `"-inf"` (JSON has no infinity, and serde_json would
//! write `null`, which does not read back as a number).

use serde::{Deserialize, Deserializer, Serializer};

/// Writes `v`.
pub fn serialize<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    if v.is_finite() {
        s.serialize_f64(*v)
    } else if v.is_nan() {
        s.serialize_str("nan")
    } else if *v > 0.0 {
        s.serialize_str("inf")
    } else {
        s.serialize_str("-inf")
    }
}

/// Reads a number, or `"inf"`, `"-inf"`, `"nan"`.
pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Num {
        F(f64),
        S(String),
    }
    match Num::deserialize(d)? {
        Num::F(x) => Ok(x),
        Num::S(s) => match s.as_str() {
            "inf" | "+inf" | "infinity" => Ok(f64::INFINITY),
            "-inf" | "-infinity" => Ok(f64::NEG_INFINITY),
            "nan" => Ok(f64::NAN),
            other => Err(serde::de::Error::custom(format!("expected a number, \"inf\" or \"-inf\", got {other:?}"))),
        },
    }
}

#[cfg(test)]
mod tests {
    #[derive(serde::Serialize, serde::Deserialize, PartialEq, Debug)]
    struct T {
        #[serde(with = "super")]
        x: f64,
    }

    #[test]
    fn round_trip() {
        for x in [1.5, f64::INFINITY, f64::NEG_INFINITY] {
            let j = serde_json::to_string(&T { x }).unwrap();
            assert_eq!(serde_json::from_str::<T>(&j).unwrap(), T { x });
        }
        assert_eq!(serde_json::to_string(&T { x: f64::INFINITY }).unwrap(), r#"{"x":"inf"}"#);
    }
}
