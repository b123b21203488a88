//! `jaus.As4Client`: an SAE AS-4 client (AS5669A over UDP) that names any message of
//! the AS-4 definitions: jaus-as4's (every set of `jaus_as4::DEFS`), a vendor's YAML on them
//! (`spec=[dirs]`, `extends: as4`), or a JSIDL import (`jsidl=[dirs]`). Messages go in as
//! a name and keyword fields and come back as dicts (`{"t", "from", "message",
//! "fields"}`), as `jaus as4-query` prints them. Over `jaus_client::as4_link`.

use std::path::PathBuf;
use std::sync::Mutex;
use std::time::Duration;

use jaus::net::as5669a::As4Id;
use jaus_client::as4_link::{As4Link, Incoming};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::convert::json_to_py;
use crate::errors::{client_error, ClientError};

/// An AS-4 client on its own UDP socket.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct As4Client {
    link: Mutex<As4Link>,
    timeout: Duration,
}

fn id(text: &str, what: &str) -> PyResult<As4Id> {
    jaus_client::as4_link::parse_id(text).map_err(|e| PyValueError::new_err(format!("{what} {e}")))
}

fn py_json(kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<serde_json::Value> {
    let Some(k) = kwargs else {
        return Ok(serde_json::json!({}));
    };
    let json = k.py().import("json")?;
    let text: String = json.call_method1("dumps", (k,))?.extract()?;
    serde_json::from_str(&text).map_err(|e| PyValueError::new_err(e.to_string()))
}

fn seconds(s: Option<f64>, default: Duration) -> PyResult<Duration> {
    match s {
        None => Ok(default),
        Some(v) if v.is_finite() && (0.0..=3600.0).contains(&v) => Ok(Duration::from_secs_f64(v)),
        Some(v) => Err(PyValueError::new_err(format!(
            "timeout {v}: 0 to 3600 seconds"
        ))),
    }
}

impl As4Client {
    fn lock(&self) -> std::sync::MutexGuard<'_, As4Link> {
        self.link.lock().unwrap_or_else(|p| p.into_inner())
    }
}

#[pymethods]
impl As4Client {
    /// A client `me` (default `"42.1.7"`) on `bind` (default any address, a free port),
    /// talking to the AS-4 node at `peer`; `spec` directories of YAML on jaus-as4's
    /// definitions, or `jsidl` directories imported instead; `timeout` seconds for
    /// answers (default 2).
    #[new]
    #[pyo3(signature = (peer, me = "42.1.7", *, bind = "0.0.0.0:0", spec = Vec::new(), jsidl = Vec::new(), timeout = 2.0))]
    fn new(
        peer: &str,
        me: &str,
        bind: &str,
        spec: Vec<PathBuf>,
        jsidl: Vec<PathBuf>,
        timeout: f64,
    ) -> PyResult<Self> {
        let peer = peer
            .parse()
            .map_err(|e| PyValueError::new_err(format!("peer {peer}: {e}")))?;
        let bind = bind
            .parse()
            .map_err(|e| PyValueError::new_err(format!("bind {bind}: {e}")))?;
        let schema = jaus_client::as4_link::schema(&spec, &jsidl).map_err(ClientError::new_err)?;
        let link =
            As4Link::open(schema, peer, bind, id(me, "me")?).map_err(ClientError::new_err)?;
        Ok(Self {
            link: Mutex::new(link),
            timeout: seconds(Some(timeout), Duration::ZERO)?,
        })
    }

    /// Sends message `name` with `fields` to component `to` (`"S.N.C"`).
    #[pyo3(signature = (to, name, **fields))]
    fn send(
        &self,
        py: Python<'_>,
        to: &str,
        name: &str,
        fields: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<()> {
        let to = id(to, "to")?;
        let json = py_json(fields)?;
        py.detach(|| {
            let mut link = self.lock();
            let m = link.message(name, &json)?;
            link.send(to, &m)
        })
        .map_err(|e| client_error(py, e, Some(name), Some(to.to_string()), None))
    }

    /// Sends query `name` with `fields` to `to` and returns its first answer as a dict
    /// (`{"t", "from", "message", "fields"}`); `ClientError` when none comes within
    /// `timeout` seconds (default the client's).
    #[pyo3(signature = (to, name, *, timeout = None, **fields))]
    fn query<'py>(
        &self,
        py: Python<'py>,
        to: &str,
        name: &str,
        timeout: Option<f64>,
        fields: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let to_id = id(to, "to")?;
        let wait = seconds(timeout, self.timeout)?;
        let json = py_json(fields)?;
        let answer = py.detach(|| {
            let mut link = self.lock();
            let m = link.message(name, &json)?;
            link.send(to_id, &m)?;
            link.receive(to_id, wait, |_| Ok(true))
        });
        match answer {
            Ok(Some(i)) => json_to_py(py, &i.json()),
            Ok(None) => Err(client_error(
                py,
                format!(
                    "{name} to {to}: no answer within {:.1} s",
                    wait.as_secs_f64()
                ),
                Some(name),
                Some(to.to_string()),
                None,
            )),
            Err(e) => Err(client_error(py, e, Some(name), Some(to.to_string()), None)),
        }
    }

    /// What component `to` sends within `timeout` seconds (default the client's), as
    /// dicts, oldest first.
    #[pyo3(signature = (to, *, timeout = None))]
    fn receive<'py>(
        &self,
        py: Python<'py>,
        to: &str,
        timeout: Option<f64>,
    ) -> PyResult<Bound<'py, PyList>> {
        let to_id = id(to, "to")?;
        let wait = seconds(timeout, self.timeout)?;
        let mut got: Vec<serde_json::Value> = Vec::new();
        py.detach(|| {
            self.lock().receive(to_id, wait, |i: &Incoming| {
                got.push(i.json());
                Ok(false)
            })
        })
        .map_err(|e| client_error(py, e, None, Some(to.to_string()), None))?;
        let list = PyList::empty(py);
        for j in &got {
            list.append(json_to_py(py, j)?)?;
        }
        Ok(list)
    }

    /// Requests control of `to` at `authority`; `ClientError` naming the answer when
    /// refused or unanswered.
    #[pyo3(signature = (to, authority))]
    fn take_control(&self, py: Python<'_>, to: &str, authority: u8) -> PyResult<()> {
        let to_id = id(to, "to")?;
        let wait = self.timeout;
        py.detach(|| self.lock().take_control(to_id, authority, wait, |_| Ok(())))
            .map_err(|e| client_error(py, e, Some("RequestControl"), Some(to.to_string()), None))
    }

    /// Gives control of `to` back (Release Control).
    #[pyo3(signature = (to))]
    fn release_control(&self, py: Python<'_>, to: &str) -> PyResult<()> {
        let to_id = id(to, "to")?;
        let wait = self.timeout;
        py.detach(|| self.lock().release_control(to_id, wait, |_| Ok(())))
            .map_err(|e| client_error(py, e, Some("ReleaseControl"), Some(to.to_string()), None))
    }
}
