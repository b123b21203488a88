//! The `links:` of a node file's communicator: UDP and QUIC data links, checked field by
//! field with file:line:column errors.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// The `links:` of host entry `i` (a communicator's data links), checked field by field
/// (`at` gives the file:line:column of a YAML path).
pub(super) fn links_at(
    v: &serde_yaml::Value,
    i: usize,
    at: &dyn Fn(&str) -> String,
) -> Result<Vec<LinkFile>, String> {
    use jaus::net::udp::link::{UdpLinkConfig, MAX_UDP_PAYLOAD};
    use serde_yaml::Value;
    let here = format!("host[{i}].links");
    let Value::Sequence(items) = v else {
        return Err(format!(
            "{}: {here}: a list of data links `- {{ id: 1, udp: {{ bind: IP:PORT, peer: IP:PORT }} }}` (or `quic:` with `cert`, `key`, `peer_cert` too)",
            at(&here)
        ));
    };
    // A mapping's keys, each known, as (key, value).
    let fields = |v: &Value, path: &str, known: &[&str]| -> Result<Vec<(String, Value)>, String> {
        let Value::Mapping(m) = v else {
            return Err(format!(
                "{}: {path}: a map with {}",
                at(path),
                known.join(", ")
            ));
        };
        let mut out = Vec::new();
        for (k, v) in m {
            let key = k.as_str().unwrap_or_default().to_string();
            if !known.contains(&key.as_str()) {
                return Err(format!(
                    "{}: {path}: unknown field `{}` (known: {})",
                    at(&format!("{path}.{key}")),
                    serde_yaml::to_string(k).unwrap_or_default().trim(),
                    known.join(", ")
                ));
            }
            out.push((key, v.clone()));
        }
        Ok(out)
    };
    let int =
        |v: &Value, path: &str, range: std::ops::RangeInclusive<u64>| -> Result<u64, String> {
            v.as_u64().filter(|n| range.contains(n)).ok_or_else(|| {
                format!(
                    "{}: {path}: {} is not an integer in {}..={}",
                    at(path),
                    serde_yaml::to_string(v).unwrap_or_default().trim(),
                    range.start(),
                    range.end()
                )
            })
        };
    let socket = |v: &Value, path: &str| -> Result<SocketAddr, String> {
        v.as_str().and_then(|s| s.parse().ok()).ok_or_else(|| {
            format!(
                "{}: {path}: {} is not a socket address IP:PORT",
                at(path),
                serde_yaml::to_string(v).unwrap_or_default().trim()
            )
        })
    };
    let file = |v: &Value, path: &str| -> Result<PathBuf, String> {
        v.as_str()
            .filter(|s| !s.is_empty())
            .map(PathBuf::from)
            .ok_or_else(|| {
                format!(
                    "{}: {path}: {} is not a file path",
                    at(path),
                    serde_yaml::to_string(v).unwrap_or_default().trim()
                )
            })
    };
    let mut links: Vec<LinkFile> = Vec::new();
    for (j, item) in items.iter().enumerate() {
        let path = format!("{here}[{j}]");
        let f = fields(item, &path, &["id", "udp", "quic"])?;
        let get = |k: &str| f.iter().find(|(n, _)| n == k).map(|(_, v)| v);
        let missing = |k: &str| format!("{}: {path}: `{k}` missing", at(&path));
        let id_path = format!("{path}.id");
        let id = int(get("id").ok_or_else(|| missing("id"))?, &id_path, 0..=255)? as u8;
        if links.iter().any(|l| l.id() == id) {
            return Err(format!(
                "{}: {id_path}: data link id {id} is used twice",
                at(&id_path)
            ));
        }
        if let Some(q) = get("quic") {
            if get("udp").is_some() {
                return Err(format!(
                    "{}: {path}: `udp` and `quic`: a data link is one or the other",
                    at(&path)
                ));
            }
            let quic_path = format!("{path}.quic");
            let quic = fields(
                q,
                &quic_path,
                &[
                    "bind",
                    "peer",
                    "cert",
                    "key",
                    "peer_cert",
                    "mtu",
                    "silence_ms",
                    "keepalive_ms",
                ],
            )?;
            let qget = |k: &str| quic.iter().find(|(n, _)| n == k).map(|(_, v)| v);
            let field = |k: &str| format!("{quic_path}.{k}");
            let need = |k: &str| {
                qget(k).ok_or_else(|| format!("{}: {quic_path}: `{k}` missing", at(&quic_path)))
            };
            let ms = |k: &str, range| -> Result<Option<Duration>, String> {
                qget(k)
                    .map(|v| int(v, &field(k), range).map(Duration::from_millis))
                    .transpose()
            };
            links.push(LinkFile::Quic(QuicLinkFile {
                id,
                bind: socket(need("bind")?, &field("bind"))?,
                peer: socket(need("peer")?, &field("peer"))?,
                cert: file(need("cert")?, &field("cert"))?,
                key: file(need("key")?, &field("key"))?,
                peer_cert: file(need("peer_cert")?, &field("peer_cert"))?,
                mtu: qget("mtu")
                    .map(|v| int(v, &field("mtu"), 16..=jaus_quic::link::MAX_MTU as u64))
                    .transpose()?
                    .map(|n| n as usize),
                silence: ms("silence_ms", 100..=3_600_000)?,
                keepalive: ms("keepalive_ms", 10..=3_600_000)?,
            }));
            continue;
        }
        let udp_path = format!("{path}.udp");
        let udp = fields(
            get("udp").ok_or_else(|| missing("udp` or `quic"))?,
            &udp_path,
            &[
                "bind",
                "peer",
                "mtu",
                "silence_ms",
                "keepalive_ms",
                "assume_up",
                "poll_ms",
            ],
        )?;
        let uget = |k: &str| udp.iter().find(|(n, _)| n == k).map(|(_, v)| v);
        let umissing = |k: &str| format!("{}: {udp_path}: `{k}` missing", at(&udp_path));
        let field = |k: &str| format!("{udp_path}.{k}");
        let bind = socket(
            uget("bind").ok_or_else(|| umissing("bind"))?,
            &field("bind"),
        )?;
        let peer = socket(
            uget("peer").ok_or_else(|| umissing("peer"))?,
            &field("peer"),
        )?;
        let mut c = UdpLinkConfig::new(id, bind, peer);
        if let Some(v) = uget("mtu") {
            c.mtu = int(v, &field("mtu"), 16..=MAX_UDP_PAYLOAD as u64)? as usize;
        }
        if let Some(v) = uget("silence_ms") {
            c.silence = Duration::from_millis(int(v, &field("silence_ms"), 10..=3_600_000)?);
        }
        if let Some(v) = uget("keepalive_ms") {
            let ms = int(v, &field("keepalive_ms"), 0..=3_600_000)?;
            c.keepalive = (ms > 0).then(|| Duration::from_millis(ms));
        }
        if let Some(v) = uget("poll_ms") {
            c.poll = Duration::from_millis(int(v, &field("poll_ms"), 1..=100)?);
        }
        if let Some(v) = uget("assume_up") {
            c.assume_up = v.as_bool().ok_or_else(|| {
                format!(
                    "{}: {}: {} is not true or false",
                    at(&field("assume_up")),
                    field("assume_up"),
                    serde_yaml::to_string(v).unwrap_or_default().trim()
                )
            })?;
        }
        links.push(LinkFile::Udp(c));
    }
    Ok(links)
}

/// A data link of a communicator's `links:` (checked field by field).
#[derive(Debug, Clone, PartialEq)]
pub enum LinkFile {
    /// `udp:`: one plain datagram per JAUS packet.
    Udp(jaus::net::udp::link::UdpLinkConfig),
    /// `quic:`: authenticated and encrypted.
    Quic(QuicLinkFile),
}

impl LinkFile {
    /// The link's id.
    pub fn id(&self) -> u8 {
        match self {
            LinkFile::Udp(c) => c.id,
            LinkFile::Quic(q) => q.id,
        }
    }

    /// The local socket address.
    pub fn bind(&self) -> SocketAddr {
        match self {
            LinkFile::Udp(c) => c.bind,
            LinkFile::Quic(q) => q.bind,
        }
    }

    /// The far end's socket address.
    pub fn peer(&self) -> SocketAddr {
        match self {
            LinkFile::Udp(c) => c.peer,
            LinkFile::Quic(q) => q.peer,
        }
    }

    /// `udp` or `quic`.
    pub fn kind(&self) -> &'static str {
        match self {
            LinkFile::Udp(_) => "udp",
            LinkFile::Quic(_) => "quic",
        }
    }

    /// The UDP link's configuration, if it is one.
    pub fn into_udp(self) -> Option<jaus::net::udp::link::UdpLinkConfig> {
        match self {
            LinkFile::Udp(c) => Some(c),
            LinkFile::Quic(_) => None,
        }
    }
}

/// `quic:` of a data link as written: `jaus_quic::QuicLinkConfig` but for the keys,
/// which are files (relative to the node file's directory) read by
/// [`QuicLinkFile::config`].
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct QuicLinkFile {
    /// The link's id.
    pub id: u8,
    /// The local socket address.
    pub bind: SocketAddr,
    /// The far end's link socket.
    pub peer: SocketAddr,
    /// This node's certificate (PEM, `jaus keygen`).
    pub cert: PathBuf,
    /// This node's private key (PEM).
    pub key: PathBuf,
    /// The far end's certificate, the only one accepted.
    pub peer_cert: PathBuf,
    /// `mtu` (default 4096).
    pub mtu: Option<usize>,
    /// `silence_ms` (default 3000).
    pub silence: Option<Duration>,
    /// `keepalive_ms` (default 1000, or a third of `silence_ms` if less).
    pub keepalive: Option<Duration>,
}

impl QuicLinkFile {
    /// The link's configuration, its key files read relative to `dir`; on error, the
    /// field (`cert`, `key` or `peer_cert`) and what is wrong (naming the file).
    pub fn config(&self, dir: &Path) -> Result<jaus_quic::QuicLinkConfig, (&'static str, String)> {
        use jaus_quic::keys;
        let cert = keys::load_cert(&dir.join(&self.cert)).map_err(|e| ("cert", e.to_string()))?;
        let key = keys::load_key(&dir.join(&self.key)).map_err(|e| ("key", e.to_string()))?;
        let peer_cert = keys::load_cert(&dir.join(&self.peer_cert))
            .map_err(|e| ("peer_cert", e.to_string()))?;
        let mut c = jaus_quic::QuicLinkConfig::new(
            self.id,
            self.bind,
            self.peer,
            jaus_quic::Identity { cert, key },
            peer_cert,
        );
        if let Some(mtu) = self.mtu {
            c.mtu = mtu;
        }
        if let Some(silence) = self.silence {
            c.silence = silence;
            c.keepalive = c.keepalive.min(silence / 3);
        }
        if let Some(keepalive) = self.keepalive {
            c.keepalive = keepalive;
        }
        Ok(c)
    }
}
