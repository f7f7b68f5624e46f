//! The query string of a request: percent-decoded `name=value` pairs, turned into the
//! options of one scene ([`SceneOptions`], checked by the library as `archstudy solve`
//! checks them) and into the window of a regime map. Every refusal names the parameter,
//! the value given and what is allowed; it becomes a 400 answer.

use crate::manifest::SceneOptions;
use std::collections::BTreeMap;

/// A refused query: the parameter, the value given and what is allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid value '{value}' for '{parameter}': {allowed}")]
pub struct QueryError {
    /// The parameter's name.
    pub parameter: String,
    /// The value given (cut to 80 characters).
    pub value: String,
    /// What is allowed.
    pub allowed: String,
}

impl QueryError {
    /// A refusal of `value` for `parameter`.
    pub fn new(parameter: &str, value: &str, allowed: impl Into<String>) -> Self {
        QueryError {
            parameter: parameter.chars().take(40).collect(),
            value: value.chars().take(80).collect(),
            allowed: allowed.into(),
        }
    }
}

/// The parameters of a scene, by the keywords of `archstudy.solve`.
pub const SCENE_PARAMETERS: [&str; 15] = [
    "k",
    "t_over_r",
    "mu",
    "half_angle",
    "weight",
    "voussoirs",
    "shape",
    "eccentricity",
    "joints",
    "keystone",
    "load",
    "at",
    "at_x",
    "width",
    "lambda",
];

/// The parameters of a regime map's window.
pub const MAP_PARAMETERS: [&str; 6] = ["k_from", "k_to", "k_steps", "mu_from", "mu_to", "mu_steps"];

/// The largest voussoir count a scene of the explorer may have: every answer stays within a
/// fraction of a second (studies and `solve` take up to the general route's own limit).
pub const MAX_EXPLORE_VOUSSOIRS: i64 = 256;

/// The longest query string taken, bytes.
pub const MAX_QUERY_BYTES: usize = 4096;

/// The decoded pairs of a query, each name once.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Query {
    pairs: BTreeMap<String, String>,
}

fn hex(b: u8) -> Option<u8> {
    match b {
        b'0'..=b'9' => Some(b - b'0'),
        b'a'..=b'f' => Some(b - b'a' + 10),
        b'A'..=b'F' => Some(b - b'A' + 10),
        _ => None,
    }
}

/// Percent-decodes one component (`+` is a space), refusing bad escapes and non-UTF-8.
fn decode(s: &str) -> Option<String> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'%' => {
                let hi = hex(*b.get(i + 1)?)?;
                let lo = hex(*b.get(i + 2)?)?;
                out.push(hi << 4 | lo);
                i += 3;
            }
            b'+' => {
                out.push(b' ');
                i += 1;
            }
            c => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8(out).ok()
}

impl Query {
    /// Parses a query string (without the `?`), allowing only the names in `allowed`.
    pub fn parse(raw: &str, allowed: &[&[&str]]) -> Result<Self, QueryError> {
        if raw.len() > MAX_QUERY_BYTES {
            return Err(QueryError::new(
                "query",
                &format!("{} bytes", raw.len()),
                format!("a query string of at most {MAX_QUERY_BYTES} bytes"),
            ));
        }
        let names: Vec<&str> = allowed.iter().flat_map(|a| a.iter().copied()).collect();
        let mut pairs = BTreeMap::new();
        for part in raw.split('&').filter(|p| !p.is_empty()) {
            let (n, v) = part.split_once('=').unwrap_or((part, ""));
            let name = decode(n)
                .ok_or_else(|| QueryError::new("query", n, "percent-encoded UTF-8 names"))?;
            let value = decode(v)
                .ok_or_else(|| QueryError::new(&name, v, "a percent-encoded UTF-8 value"))?;
            if !names.contains(&name.as_str()) {
                return Err(QueryError::new(
                    &name,
                    &value,
                    format!("unknown parameter; allowed: {}", names.join(", ")),
                ));
            }
            if pairs.insert(name.clone(), value.clone()).is_some() {
                return Err(QueryError::new(&name, &value, "each parameter once"));
            }
        }
        Ok(Query { pairs })
    }

    /// The value of a parameter, when given and not empty.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.pairs
            .get(name)
            .map(String::as_str)
            .filter(|v| !v.is_empty())
    }

    /// A number, when given: finite, or `inf` where `infinite` allows it.
    pub fn number(&self, name: &str, infinite: bool) -> Result<Option<f64>, QueryError> {
        let Some(v) = self.get(name) else {
            return Ok(None);
        };
        let x = match v.trim() {
            "inf" | "∞" | "infinity" | "Infinity" if infinite => f64::INFINITY,
            t => t
                .parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .ok_or_else(|| {
                    QueryError::new(
                        name,
                        v,
                        if infinite {
                            "a finite number or inf"
                        } else {
                            "a finite number"
                        },
                    )
                })?,
        };
        Ok(Some(x))
    }

    /// An integer, when given.
    pub fn integer(&self, name: &str) -> Result<Option<i64>, QueryError> {
        self.get(name)
            .map(|v| {
                v.trim()
                    .parse::<i64>()
                    .map_err(|_| QueryError::new(name, v, "an integer"))
            })
            .transpose()
    }

    /// The options of the scene the query gives (the defaults of `archstudy solve` for what
    /// it leaves out), with the find `find`.
    pub fn scene_options(&self, find: &str) -> Result<SceneOptions, QueryError> {
        let d = SceneOptions::default();
        let text = |name: &str, default: &str| self.get(name).unwrap_or(default).to_string();
        let voussoirs = match self.get("voussoirs") {
            None | Some("continuum") => None,
            Some(_) => {
                let n = self.integer("voussoirs")?;
                if let Some(n) = n
                    && !(1..=MAX_EXPLORE_VOUSSOIRS).contains(&n)
                {
                    return Err(QueryError::new(
                        "voussoirs",
                        &n.to_string(),
                        format!(
                            "continuum or a count from 1 to {MAX_EXPLORE_VOUSSOIRS} (larger \
                             counts: archstudy solve or a study)"
                        ),
                    ));
                }
                n
            }
        };
        let keystone = match self.get("keystone") {
            None | Some("false" | "0" | "no") => false,
            Some("true" | "1" | "yes") => true,
            Some(v) => return Err(QueryError::new("keystone", v, "true or false")),
        };
        Ok(SceneOptions {
            k: self.number("k", false)?,
            t_over_r: self.number("t_over_r", false)?,
            mu: self.number("mu", true)?.unwrap_or(d.mu),
            half_angle_deg: self
                .number("half_angle", false)?
                .unwrap_or(d.half_angle_deg),
            weight: text("weight", &d.weight),
            voussoirs,
            find: find.to_string(),
            shape: text("shape", &d.shape),
            eccentricity: self.number("eccentricity", false)?,
            joints: text("joints", &d.joints),
            keystone,
            load: text("load", &d.load),
            at_deg: self.number("at", false)?,
            at_x: self.number("at_x", false)?,
            width: self.number("width", false)?,
            lambda: self.number("lambda", false)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCENE: &[&[&str]] = &[&SCENE_PARAMETERS];

    #[test]
    fn a_query_decodes_to_the_options_of_its_scene() {
        let q = Query::parse(
            "k=1.2&mu=inf&half_angle=60&load=point&at_x=0.25&lambda=0.1",
            SCENE,
        )
        .unwrap();
        let o = q.scene_options("state").unwrap();
        assert_eq!(o.k, Some(1.2));
        assert_eq!(o.mu, f64::INFINITY);
        assert_eq!(o.half_angle_deg, 60.0);
        assert_eq!(o.at_x, Some(0.25));
        assert_eq!(o.load, "point");
        let q = Query::parse("mu=0.35&weight=centreline&voussoirs=12&keystone=1", SCENE).unwrap();
        let o = q.scene_options("state").unwrap();
        assert_eq!((o.mu, o.voussoirs, o.keystone), (0.35, Some(12), true));
        assert_eq!(o.weight, "centreline");
        let q = Query::parse("shape=pointed&eccentricity=0.2&joints=vertical", SCENE).unwrap();
        let o = q.scene_options("state").unwrap();
        assert_eq!((o.shape.as_str(), o.eccentricity), ("pointed", Some(0.2)));
        assert_eq!(o.joints, "vertical");
    }

    #[test]
    fn every_refusal_names_its_parameter_and_value() {
        let err = |raw: &str| Query::parse(raw, SCENE).and_then(|q| q.scene_options("state"));
        let e = err("k=abc").unwrap_err();
        assert_eq!((e.parameter.as_str(), e.value.as_str()), ("k", "abc"));
        assert!(e.allowed.contains("finite number"));
        let e = err("colour=red").unwrap_err();
        assert_eq!(e.parameter, "colour");
        assert!(e.allowed.contains("half_angle"), "{}", e.allowed);
        let e = err("k=1.2&k=1.3").unwrap_err();
        assert_eq!(
            (e.parameter.as_str(), e.allowed.as_str()),
            ("k", "each parameter once")
        );
        let e = err("voussoirs=100000").unwrap_err();
        assert_eq!(e.parameter, "voussoirs");
        assert!(e.allowed.contains("256"));
        let e = err("keystone=maybe").unwrap_err();
        assert_eq!(e.parameter, "keystone");
        let e = err("mu=%zz").unwrap_err();
        assert_eq!(e.parameter, "mu");
        let e = err("k=inf").unwrap_err();
        assert_eq!(e.parameter, "k");
        let e = err(&"k=1&".repeat(2000)).unwrap_err();
        assert_eq!(e.parameter, "query");
    }
}
