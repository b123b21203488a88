//! `jaus.Client`: the network from Python, as the `jaus` CLI joins it. A thread of its
//! own (Rust, no GIL) runs the CLI's place in the system (`jaus_client`: discovery,
//! heartbeats, its System Commander) and answers Python's `send`, `query`,
//! `control` and `watch`; Python waits with the GIL released.

mod confirmation;
mod feed;
mod io;

use std::net::{SocketAddr, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{mpsc, Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use jaus::net::Framing;
use jaus::{Address, CommandCode};
use jaus_client::catalogue::Catalogue;
use pyo3::exceptions::{PyStopIteration, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::catalog::{sdk, Catalog};
use crate::convert::json_to_py;
use crate::errors::{client_error, decode_error_text};
use crate::message::{address, Message};
use crate::schema::Schema;
pub use confirmation::Confirmation;
use feed::{Cmd, Failure, Feed, Pop, Reply, Stats};
use io::{Io, Joined};

/// Commands from Python queued for the I/O thread at most (a caller waits beyond).
const COMMANDS: usize = 256;
/// How much longer than its own time limit Python waits for the thread's answer.
const GRACE: Duration = Duration::from_secs(2);

/// The peers: `"host:port"` or a list of them.
fn peers(obj: Option<&Bound<'_, PyAny>>) -> PyResult<Vec<SocketAddr>> {
    let texts: Vec<String> = match obj {
        None => vec!["127.0.0.1:3794".into()],
        Some(o) => match o.extract::<String>() {
            Ok(s) => vec![s],
            Err(_) => o
                .extract::<Vec<String>>()
                .map_err(|_| PyValueError::new_err("peer: \"host:port\" or a list of them"))?,
        },
    };
    let mut out = Vec::new();
    for t in texts {
        let found = t
            .to_socket_addrs()
            .map_err(|e| PyValueError::new_err(format!("peer {t}: {e}")))?;
        out.extend(found.filter(SocketAddr::is_ipv4).take(1));
    }
    Ok(out)
}

fn seconds(t: f64, what: &str) -> PyResult<Duration> {
    Duration::try_from_secs_f64(t)
        .map_err(|_| PyValueError::new_err(format!("{what}: {t} is not a time in seconds")))
}

/// Waits for the I/O thread's answer with the GIL released, seeing Ctrl-C.
fn wait<T: Send>(
    py: Python<'_>,
    mut rx: mpsc::Receiver<Result<T, Failure>>,
    limit: Duration,
) -> PyResult<Result<T, Failure>> {
    let end = Instant::now() + limit + GRACE;
    loop {
        // The receiver goes to the GIL-free side and back (it is not Sync).
        let (got, back) = py.detach(move || {
            let got = rx.recv_timeout(Duration::from_millis(100));
            (got, rx)
        });
        rx = back;
        match got {
            Ok(r) => return Ok(r),
            Err(mpsc::RecvTimeoutError::Timeout) => {
                py.check_signals()?;
                if Instant::now() >= end {
                    return Ok(Err(Failure::new("the client's I/O thread did not answer")));
                }
            }
            Err(mpsc::RecvTimeoutError::Disconnected) => {
                return Ok(Err(Failure::new("the client is closed")))
            }
        }
    }
}

/// A member of a JAUS system from Python: joins the peers as the `jaus` CLI does
/// (`--peer`, `--me`, `--bind`, `--mode`), with a System Commander of its own.
#[pyclass(module = "jaus", frozen, subclass)]
#[derive(Debug)]
pub struct Client {
    me: Address,
    local: SocketAddr,
    joined: bool,
    timeout: Duration,
    cat: Arc<Catalog>,
    codes: Catalogue,
    stats: Arc<Stats>,
    tx: Mutex<Option<mpsc::SyncSender<Cmd>>>,
    thread: Mutex<Option<JoinHandle<()>>>,
    next_watch: AtomicU64,
}

impl Client {
    fn sender(&self) -> Option<mpsc::SyncSender<Cmd>> {
        self.tx.lock().unwrap_or_else(|p| p.into_inner()).clone()
    }

    /// Hands `cmd` to the I/O thread (waiting while its queue is full).
    fn submit(&self, py: Python<'_>, cmd: Cmd) -> PyResult<()> {
        let Some(tx) = self.sender() else {
            return Err(client_error(
                py,
                "the client is closed".into(),
                None,
                None,
                None,
            ));
        };
        py.detach(|| tx.send(cmd)).map_err(|_| {
            client_error(
                py,
                "the client's I/O thread has stopped".into(),
                None,
                None,
                None,
            )
        })
    }

    /// Sends `cmd` (made with the answer's sender) and waits for its answer.
    fn call<T: Send>(
        &self,
        py: Python<'_>,
        limit: Duration,
        make: impl FnOnce(Reply<T>) -> Cmd,
        message: Option<&str>,
        to: Option<Address>,
    ) -> PyResult<T> {
        let (reply, rx) = mpsc::sync_channel(1);
        self.submit(py, make(reply))?;
        wait(py, rx, limit)?.map_err(|f| {
            client_error(
                py,
                f.text,
                message,
                to.map(|a| a.to_string()),
                f.response_code,
            )
        })
    }

    fn limit(&self, timeout: Option<f64>) -> PyResult<Duration> {
        timeout.map_or(Ok(self.timeout), |t| seconds(t, "timeout"))
    }

    /// The message's body, code and name, by the schema it was made with.
    fn body(py: Python<'_>, message: &Message) -> PyResult<(CommandCode, &'static str, Vec<u8>)> {
        let body = message.cat.encode(py, message.msg(py)?)?;
        Ok((message.code(), message.name(), body))
    }

    /// The code of the report answering `query` (`report` names it when the
    /// definitions do not).
    fn report_of(
        &self,
        py: Python<'_>,
        query: &Message,
        report: Option<&str>,
    ) -> PyResult<CommandCode> {
        if let Some(r) = report {
            return self
                .cat
                .schema
                .message(r)
                .map(|m| m.code)
                .ok_or_else(|| PyValueError::new_err(format!("report: no message named {r}")));
        }
        self.codes.answer_of(query.code()).ok_or_else(|| {
            client_error(
                py,
                format!(
                    "{}: not a query (no report answers it); give report=NAME",
                    query.name()
                ),
                Some(query.name()),
                None,
                None,
            )
        })
    }

    fn end(&self, py: Python<'_>) {
        let tx = self.tx.lock().unwrap_or_else(|p| p.into_inner()).take();
        if let Some(tx) = tx {
            let _ = py.detach(|| tx.send(Cmd::Close));
        }
        let thread = self.thread.lock().unwrap_or_else(|p| p.into_inner()).take();
        if let Some(t) = thread {
            let _ = py.detach(|| t.join());
        }
    }
}

#[pymethods]
impl Client {
    /// Joins the system at `peer` (`"host:port"` or a list; default
    /// `"127.0.0.1:3794"`) as `me` (default: the CLI's, S.1.40.1 with S in 200-253),
    /// on `bind` (default: the CLI's choice, port 3794 of an address of its own), and
    /// waits until the peers answered and know it (at most `timeout` seconds).
    #[new]
    #[pyo3(signature = (peer = None, me = None, *, bind = None, timeout = 5.0, mode = "auto", schema = None, name = "jaus Python client"))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        peer: Option<&Bound<'_, PyAny>>,
        me: Option<&Bound<'_, PyAny>>,
        bind: Option<&str>,
        timeout: f64,
        mode: &str,
        schema: Option<PyRef<'_, Schema>>,
        name: &str,
    ) -> PyResult<Client> {
        if name.is_empty() || name.len() > 255 {
            return Err(PyValueError::new_err(format!(
                "name {name:?}: 1 to 255 bytes (it is sent in Report Identification)"
            )));
        }
        let timeout = seconds(timeout, "timeout")?;
        let me = match me {
            Some(m) => address(m, "me")?,
            None => jaus_client::default_me(),
        };
        let bind = bind
            .map(|b| {
                b.parse::<SocketAddr>()
                    .map_err(|e| PyValueError::new_err(format!("bind {b}: {e}")))
            })
            .transpose()?;
        let mode: jaus_client::Mode = mode.parse().map_err(PyValueError::new_err)?;
        let cfg = jaus_client::Client {
            me,
            bind,
            peers: peers(peer)?,
            carrier: jaus_client::Carrier::Udp,
            name: name.to_string(),
            framing: Framing::Judp,
            wait: timeout,
            mode,
            // Python asks per command (`send(..., confirm=True)`).
            confirm: false,
        };
        let cat = match schema {
            Some(s) => s.cat.clone(),
            None => sdk()?,
        };
        let stats = Arc::new(Stats::default());
        let (ready_tx, ready_rx) = mpsc::sync_channel::<Result<Joined, Failure>>(1);
        let (tx, rx) = mpsc::sync_channel::<Cmd>(COMMANDS);
        let (thread_cat, thread_stats) = (cat.clone(), stats.clone());
        let thread = std::thread::Builder::new()
            .name(format!("jaus-client {me}"))
            .spawn(move || {
                let mut io = match Io::start(cfg, thread_cat, thread_stats) {
                    Ok(io) => io,
                    Err(e) => {
                        let _ = ready_tx.send(Err(Failure::new(e)));
                        return;
                    }
                };
                if let Err(e) = io.settle(timeout) {
                    let _ = ready_tx.send(Err(Failure::new(e)));
                    return;
                }
                let _ = ready_tx.send(Ok(io.joined()));
                io.run(rx);
            })
            .map_err(|e| PyValueError::new_err(format!("cannot start the client's thread: {e}")))?;
        let joined = match wait(py, ready_rx, timeout)? {
            Ok(j) => j,
            Err(f) => {
                drop(tx);
                let _ = py.detach(|| thread.join());
                return Err(client_error(py, f.text, None, None, None));
            }
        };
        Ok(Client {
            me,
            local: joined.local,
            joined: joined.joined,
            timeout,
            cat,
            codes: Catalogue::sdk(),
            stats,
            tx: Mutex::new(Some(tx)),
            thread: Mutex::new(Some(thread)),
            next_watch: AtomicU64::new(1),
        })
    }

    /// This client's address, `"s.n.c.i"`.
    #[getter]
    fn me(&self) -> String {
        self.me.to_string()
    }

    /// The local socket, `(ip, port)`.
    #[getter]
    fn local(&self) -> (String, u16) {
        (self.local.ip().to_string(), self.local.port())
    }

    /// Whether the client joined the peer's node as one of its components (else it
    /// runs a node of its own).
    #[getter]
    fn joined(&self) -> bool {
        self.joined
    }

    /// Whether the client was closed.
    #[getter]
    fn closed(&self) -> bool {
        self.sender().is_none()
    }

    /// The system tree as `jaus discover --json` prints it: `{"subsystems": [{"id",
    /// "name", "nodes": [{"id", "name", "components": [{"address", "name",
    /// "services"}]}]}]}`.
    fn tree<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let tree = self.call(py, self.timeout, |reply| Cmd::Tree { reply }, None, None)?;
        json_to_py(py, &tree)
    }

    /// Sends `message` to `dest`. Commands ask for an acknowledgement as the CLI's do;
    /// with `ack=True` this waits for it and raises `jaus.ClientError` on a NAK (with
    /// the receiver's reason) or when none comes within `timeout`. With
    /// `confirm=True` it confirms the command by its effect and returns a
    /// `jaus.Confirmation` (`.outcome` `"acknowledged"` or `"confirmed_by_readback"`,
    /// `.detail`), or raises `jaus.ClientError` (`.outcome` `"refused"` or
    /// `"not_confirmed"`, `.detail` naming what is known); `ack` is then implied.
    #[pyo3(signature = (dest, message, *, ack = false, confirm = false, timeout = None))]
    #[allow(clippy::too_many_arguments)]
    fn send(
        &self,
        py: Python<'_>,
        dest: &Bound<'_, PyAny>,
        message: PyRef<'_, Message>,
        ack: bool,
        confirm: bool,
        timeout: Option<f64>,
    ) -> PyResult<Option<Confirmation>> {
        let to = address(dest, "dest")?;
        let (code, name, body) = Client::body(py, &message)?;
        if confirm {
            let limit = self.limit(timeout)?;
            // The command's departure (its node may hold it behind an unanswered one),
            // the acknowledgement waited for (at most `limit`), then the read-back.
            let end = self.call(
                py,
                limit.saturating_mul(2) + jaus_client::confirm::HELD_AT_MOST,
                |reply| Cmd::Send {
                    to,
                    code,
                    name,
                    body,
                    ack: None,
                    confirm: Some((limit, reply)),
                },
                Some(name),
                Some(to),
            )?;
            if end.confirmed() {
                return Ok(Some(Confirmation::of(&end)));
            }
            let err = client_error(
                py,
                format!("{name} to {to}: {end}"),
                Some(name),
                Some(to.to_string()),
                None,
            );
            let value = err.value(py);
            value.setattr("outcome", end.outcome())?;
            value.setattr("detail", end.detail())?;
            return Err(err);
        }
        if !ack {
            return self
                .submit(
                    py,
                    Cmd::Send {
                        to,
                        code,
                        name,
                        body,
                        ack: None,
                        confirm: None,
                    },
                )
                .map(|()| None);
        }
        let limit = self.limit(timeout)?;
        self.call(
            py,
            limit,
            |reply| Cmd::Send {
                to,
                code,
                name,
                body,
                ack: Some((limit, reply)),
                confirm: None,
            },
            Some(name),
            Some(to),
        )
        .map(|()| None)
    }

    /// Sends the query `message` to `dest` and returns its report (`report` names the
    /// report when the definitions do not say it). Raises `jaus.ClientError` naming
    /// the query and the address when none comes within `timeout`.
    #[pyo3(signature = (dest, message, *, timeout = None, report = None))]
    fn query(
        &self,
        py: Python<'_>,
        dest: &Bound<'_, PyAny>,
        message: PyRef<'_, Message>,
        timeout: Option<f64>,
        report: Option<&str>,
    ) -> PyResult<Message> {
        let to = address(dest, "dest")?;
        let answer = self.report_of(py, &message, report)?;
        let (code, name, body) = Client::body(py, &message)?;
        let limit = self.limit(timeout)?;
        let m = self.call(
            py,
            limit,
            |reply| Cmd::Query {
                to,
                code,
                name,
                body,
                answer,
                wait: limit,
                reply,
            },
            Some(name),
            Some(to),
        )?;
        Ok(Message::new(self.cat.clone(), m))
    }

    /// Control of `dest` as a context manager: requested on entry (with `authority`,
    /// default the client's own), kept (asked for again when a higher authority takes
    /// it), given back on exit. Entry raises `jaus.ControlRefused` naming the response
    /// code when the component refuses.
    #[pyo3(signature = (dest, *, authority = None, timeout = None))]
    fn control(
        slf: &Bound<'_, Self>,
        dest: &Bound<'_, PyAny>,
        authority: Option<u8>,
        timeout: Option<f64>,
    ) -> PyResult<Control> {
        let to = address(dest, "dest")?;
        let limit = slf.get().limit(timeout)?;
        Ok(Control {
            client: slf.clone().unbind(),
            to,
            authority,
            limit,
            held: AtomicBool::new(false),
        })
    }

    /// The reports answering `query` from `dest`, as they come: through a service
    /// connection at `periodic_hz` (presence vector `presence`, default the query's
    /// `presence_vector`), or an event on every change when `periodic_hz` is None.
    /// Returns once the provider confirmed (else raises `jaus.ClientError`). At most
    /// `queue` reports wait to be read; older ones are dropped and counted.
    #[pyo3(signature = (dest, query, *, periodic_hz = None, presence = None, queue = 64, timeout = None, report = None))]
    #[allow(clippy::too_many_arguments)]
    fn watch(
        &self,
        py: Python<'_>,
        dest: &Bound<'_, PyAny>,
        query: PyRef<'_, Message>,
        periodic_hz: Option<f64>,
        presence: Option<u32>,
        queue: usize,
        timeout: Option<f64>,
        report: Option<&str>,
    ) -> PyResult<Watch> {
        let to = address(dest, "dest")?;
        let report = self.report_of(py, &query, report)?;
        let (code, name, query_body) = Client::body(py, &query)?;
        let fields = &query.msg(py)?.fields;
        let presence = presence.unwrap_or_else(|| match fields.field("presence_vector") {
            Some(jaus_dynamic::Value::UInt(p)) => u32::try_from(*p).unwrap_or(u32::MAX),
            _ => 0,
        });
        if let Some(hz) = periodic_hz {
            if !(hz.is_finite() && hz > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "periodic_hz: {hz}: a rate above 0 Hz"
                )));
            }
        }
        let limit = self.limit(timeout)?;
        let feed = Arc::new(Feed::new(queue));
        let id = self.next_watch.fetch_add(1, Ordering::Relaxed);
        let cmd_feed = feed.clone();
        self.call(
            py,
            limit,
            |reply| Cmd::Watch {
                id,
                to,
                query: code,
                query_body,
                report,
                periodic_hz,
                presence,
                feed: cmd_feed,
                wait: limit,
                reply,
            },
            Some(name),
            Some(to),
        )?;
        Ok(Watch {
            tx: Mutex::new(self.sender()),
            id,
            feed,
            cat: self.cat.clone(),
            stats: self.stats.clone(),
        })
    }

    /// The client's counters: datagrams and messages received, messages sent,
    /// messages nobody waited for (`unclaimed`), reports dropped by full watch queues,
    /// decode errors, NAKs, control lost, commands dropped, send errors.
    fn stats<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, v) in self.stats.snapshot() {
            d.set_item(k, v)?;
        }
        Ok(d)
    }

    /// Ends every watch, gives control back and stops the client's thread.
    fn close(&self, py: Python<'_>) {
        self.end(py);
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    #[pyo3(signature = (*_args))]
    fn __exit__(&self, py: Python<'_>, _args: &Bound<'_, pyo3::types::PyTuple>) -> bool {
        self.end(py);
        false
    }

    fn __repr__(&self) -> String {
        format!(
            "jaus.Client(me={}, local={}, {})",
            self.me,
            self.local,
            if self.joined { "joined" } else { "own node" }
        )
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        let tx = self.tx.lock().unwrap_or_else(|p| p.into_inner()).take();
        if let Some(tx) = tx {
            let _ = tx.try_send(Cmd::Close);
        }
        let thread = self.thread.lock().unwrap_or_else(|p| p.into_inner()).take();
        if let Some(t) = thread {
            let _ = t.join();
        }
    }
}

/// Control of one component, from `Client.control(...)`: `with` it, or `acquire()`
/// and `release()`.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Control {
    client: Py<Client>,
    to: Address,
    authority: Option<u8>,
    limit: Duration,
    held: AtomicBool,
}

#[pymethods]
impl Control {
    /// The component, `"s.n.c.i"`.
    #[getter]
    fn address(&self) -> String {
        self.to.to_string()
    }

    /// Whether control is held (taken and not given back).
    #[getter]
    fn held(&self) -> bool {
        self.held.load(Ordering::Relaxed)
    }

    /// Requests control and waits until it is granted; raises `jaus.ControlRefused`
    /// (with `.response_code`) when refused, `jaus.ClientError` when unanswered.
    fn acquire(&self, py: Python<'_>) -> PyResult<()> {
        let (to, authority, limit) = (self.to, self.authority, self.limit);
        self.client.get().call(
            py,
            limit,
            |reply| Cmd::Keep {
                to,
                authority,
                wait: limit,
                reply,
            },
            Some("RequestComponentControl"),
            Some(to),
        )?;
        self.held.store(true, Ordering::Relaxed);
        Ok(())
    }

    /// Gives control back (nothing when the client is closed: closing gave it back).
    fn release(&self, py: Python<'_>) -> PyResult<()> {
        if !self.held.swap(false, Ordering::Relaxed) {
            return Ok(());
        }
        let client = self.client.get();
        if client.closed() {
            return Ok(());
        }
        let to = self.to;
        client.call(
            py,
            client.timeout,
            |reply| Cmd::Release { to, reply },
            Some("ReleaseComponentControl"),
            Some(to),
        )
    }

    fn __enter__(slf: Bound<'_, Self>) -> PyResult<Bound<'_, Self>> {
        slf.get().acquire(slf.py())?;
        Ok(slf)
    }

    #[pyo3(signature = (*_args))]
    fn __exit__(&self, py: Python<'_>, _args: &Bound<'_, pyo3::types::PyTuple>) -> PyResult<bool> {
        self.release(py)?;
        Ok(false)
    }

    fn __repr__(&self) -> String {
        format!(
            "jaus.Control({}, held={})",
            self.to,
            self.held.load(Ordering::Relaxed)
        )
    }
}

/// The reports of one `Client.watch(...)`: an iterator (blocking, the GIL released),
/// `get(timeout)`, and `close()` (also on exit of `with`, garbage collection, and the
/// client's close), which ends the service connection or event at the provider.
#[pyclass(module = "jaus", frozen)]
#[derive(Debug)]
pub struct Watch {
    tx: Mutex<Option<mpsc::SyncSender<Cmd>>>,
    id: u64,
    feed: Arc<Feed>,
    cat: Arc<Catalog>,
    stats: Arc<Stats>,
}

impl Watch {
    fn item(&self, py: Python<'_>, item: feed::Item) -> PyResult<Message> {
        item.map(|m| Message::new(self.cat.clone(), m))
            .map_err(|e| decode_error_text(py, e, None))
    }

    fn stop(&self, blocking: Option<Python<'_>>) {
        let tx = self.tx.lock().unwrap_or_else(|p| p.into_inner()).take();
        self.feed.end("closed");
        if let Some(tx) = tx {
            let cmd = Cmd::Unwatch { id: self.id };
            let sent = match blocking {
                Some(py) => py.detach(|| tx.send(cmd)).is_ok(),
                None => tx.try_send(cmd).is_ok(),
            };
            if !sent {
                Stats::add(&self.stats.commands_dropped);
            }
        }
    }
}

#[pymethods]
impl Watch {
    fn __iter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<Message> {
        loop {
            match py.detach(|| self.feed.pop(None)) {
                Pop::Item(item) => return self.item(py, item),
                Pop::Empty => py.check_signals()?,
                Pop::Ended => return Err(PyStopIteration::new_err(())),
            }
        }
    }

    /// The next report, or None when none came within `timeout` seconds (None: wait
    /// until one comes) or the watch ended.
    #[pyo3(signature = (timeout = None))]
    fn get(&self, py: Python<'_>, timeout: Option<f64>) -> PyResult<Option<Message>> {
        let end = timeout
            .map(|t| seconds(t, "timeout"))
            .transpose()?
            .map(|d| Instant::now() + d);
        loop {
            let left = end.map(|e| e.saturating_duration_since(Instant::now()));
            let step = left.map_or(Duration::from_millis(100), |l| {
                l.min(Duration::from_millis(100))
            });
            match py.detach(|| self.feed.pop(Some(step))) {
                Pop::Item(item) => return self.item(py, item).map(Some),
                Pop::Ended => return Ok(None),
                Pop::Empty => {
                    py.check_signals()?;
                    if end.is_some_and(|e| Instant::now() >= e) {
                        return Ok(None);
                    }
                }
            }
        }
    }

    /// Whether the watch ended (closed, or its client closed).
    #[getter]
    fn closed(&self) -> bool {
        self.feed.ended().is_some()
    }

    /// Why the watch ended (`"closed"`, `"the client closed"`, a refusal), or None.
    #[getter]
    fn end_reason(&self) -> Option<String> {
        self.feed.ended()
    }

    /// Reports dropped because they were not read in time.
    #[getter]
    fn dropped(&self) -> u64 {
        self.feed.dropped()
    }

    /// Ends the service connection or event.
    fn close(&self, py: Python<'_>) {
        self.stop(Some(py));
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    #[pyo3(signature = (*_args))]
    fn __exit__(&self, py: Python<'_>, _args: &Bound<'_, pyo3::types::PyTuple>) -> bool {
        self.stop(Some(py));
        false
    }
}

impl Drop for Watch {
    fn drop(&mut self) {
        self.stop(None);
    }
}
