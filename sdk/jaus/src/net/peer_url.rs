//! [`PeerUrl`]: where a peer is and which transport reaches it, as a node file and the
//! CLI's `--peer` write it: `HOST:PORT` or `udp://HOST:PORT` (JUDP), `tcp://HOST:PORT`
//! (JTCP), `serial:///dev/ttyUSB0?baud=57600` (JSerial).

use std::net::{SocketAddr, ToSocketAddrs};
use std::path::PathBuf;

/// The speed of a serial line when its URL names none.
pub const DEFAULT_BAUD: u32 = 57_600;

/// A peer and its transport.
///
/// ```
/// use jaus::net::PeerUrl;
/// let p: PeerUrl = "tcp://127.0.0.1:3794".parse().unwrap();
/// assert_eq!(p, PeerUrl::Tcp("127.0.0.1:3794".parse().unwrap()));
/// let s: PeerUrl = "serial:///dev/ttyUSB0?baud=115200".parse().unwrap();
/// assert_eq!(s, PeerUrl::Serial { path: "/dev/ttyUSB0".into(), baud: 115_200 });
/// assert_eq!(s.to_string(), "serial:///dev/ttyUSB0?baud=115200");
/// let u: PeerUrl = "127.0.0.1:3794".parse().unwrap();
/// assert!(matches!(u, PeerUrl::Udp(_)));
/// assert!("ftp://x".parse::<PeerUrl>().unwrap_err().contains("tcp://HOST:PORT"));
/// ```
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum PeerUrl {
    /// JUDP over UDP.
    Udp(SocketAddr),
    /// JTCP over TCP.
    Tcp(SocketAddr),
    /// JSerial over a serial line.
    Serial {
        /// The device (`/dev/ttyUSB0`, a pseudo-terminal).
        path: PathBuf,
        /// Bits per second.
        baud: u32,
    },
}

impl PeerUrl {
    /// The socket address of a UDP or TCP peer.
    pub fn socket_addr(&self) -> Option<SocketAddr> {
        match self {
            PeerUrl::Udp(a) | PeerUrl::Tcp(a) => Some(*a),
            PeerUrl::Serial { .. } => None,
        }
    }

    /// The transport's name: `udp`, `tcp` or `serial`.
    pub fn scheme(&self) -> &'static str {
        match self {
            PeerUrl::Udp(_) => "udp",
            PeerUrl::Tcp(_) => "tcp",
            PeerUrl::Serial { .. } => "serial",
        }
    }
}

impl std::fmt::Display for PeerUrl {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PeerUrl::Udp(a) => write!(f, "{a}"),
            PeerUrl::Tcp(a) => write!(f, "tcp://{a}"),
            PeerUrl::Serial { path, baud } => {
                write!(f, "serial://{}?baud={baud}", path.display())
            }
        }
    }
}

/// `HOST:PORT`, resolved to its first address.
fn resolve(text: &str, whole: &str) -> Result<SocketAddr, String> {
    if let Ok(a) = text.parse() {
        return Ok(a);
    }
    text.to_socket_addrs()
        .map_err(|e| format!("`{whole}`: {e}"))?
        .next()
        .ok_or_else(|| format!("`{whole}`: {text} has no address"))
}

impl std::str::FromStr for PeerUrl {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let usage = "expected HOST:PORT or udp://HOST:PORT (JUDP), tcp://HOST:PORT (JTCP) or serial:///dev/DEVICE?baud=N (JSerial)";
        let Some((scheme, rest)) = s.split_once("://") else {
            return resolve(s, s)
                .map(PeerUrl::Udp)
                .map_err(|e| format!("{e}; {usage}"));
        };
        match scheme {
            "udp" => Ok(PeerUrl::Udp(resolve(rest, s)?)),
            "tcp" => Ok(PeerUrl::Tcp(resolve(rest, s)?)),
            "serial" => {
                let (path, query) = rest.split_once('?').unwrap_or((rest, ""));
                if !path.starts_with('/') {
                    return Err(format!(
                        "`{s}`: a serial line is an absolute device path (serial:///dev/ttyUSB0)"
                    ));
                }
                let mut baud = DEFAULT_BAUD;
                for pair in query.split('&').filter(|p| !p.is_empty()) {
                    match pair.split_once('=') {
                        Some(("baud", v)) => {
                            baud = v
                                .parse()
                                .ok()
                                .filter(|b| *b > 0)
                                .ok_or_else(|| format!("`{s}`: baud `{v}` is not a speed"))?;
                        }
                        _ => return Err(format!("`{s}`: unknown option `{pair}` (baud=N)")),
                    }
                }
                Ok(PeerUrl::Serial {
                    path: PathBuf::from(path),
                    baud,
                })
            }
            other => Err(format!("`{s}`: unknown transport `{other}`; {usage}")),
        }
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for PeerUrl {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        s.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_text_and_the_forms() {
        let e = "serial://dev/tty".parse::<PeerUrl>().unwrap_err();
        assert!(e.contains("absolute device path"), "{e}");
        let e = "serial:///dev/tty?baud=fast"
            .parse::<PeerUrl>()
            .unwrap_err();
        assert!(e.contains("baud `fast`"), "{e}");
        let e = "serial:///dev/tty?parity=odd"
            .parse::<PeerUrl>()
            .unwrap_err();
        assert!(e.contains("unknown option `parity=odd`"), "{e}");
        let e = "tcp://nohost".parse::<PeerUrl>().unwrap_err();
        assert!(e.contains("tcp://nohost"), "{e}");
        assert_eq!(
            "serial:///dev/pts/3".parse::<PeerUrl>().unwrap(),
            PeerUrl::Serial {
                path: "/dev/pts/3".into(),
                baud: DEFAULT_BAUD
            }
        );
        assert_eq!(
            "udp://127.0.0.1:9".parse::<PeerUrl>().unwrap().to_string(),
            "127.0.0.1:9"
        );
    }
}
