//! Mutual authentication by pinning: rustls verifiers that accept exactly one
//! certificate, the far end's, and the TLS configurations of the two ends of a link
//! built on them.
//!
//! * [`PinnedServer`] (the connecting end): the server's certificate must be, byte for
//!   byte (DER), the pinned one; its name, issuer and dates are not looked at, there is
//!   no certificate authority.
//! * [`PinnedClient`] (the accepting end): a client certificate is required and must be
//!   the pinned one.
//!
//! Both still verify the TLS 1.3 handshake signature with the certificate's key
//! (`rustls::crypto::verify_tls13_signature`, the ring provider's algorithms), so that a
//! copy of the certificate without its private key gets nowhere. TLS 1.2 is refused
//! (QUIC needs TLS 1.3 anyway, and the configurations offer only 1.3). Every
//! certificate refused is counted in the `refused` counter the verifier was made with.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;

use rustls::client::danger::{HandshakeSignatureValid, ServerCertVerified, ServerCertVerifier};
use rustls::crypto::{CryptoProvider, WebPkiSupportedAlgorithms};
use rustls::pki_types::{CertificateDer, ServerName, UnixTime};
use rustls::server::danger::{ClientCertVerified, ClientCertVerifier};
use rustls::{CertificateError, DigitallySignedStruct, DistinguishedName, SignatureScheme};

use crate::keys::Identity;

/// The ALPN protocol of a JAUS data link: both ends offer only this, so that a link
/// never talks to another QUIC service by mistake.
pub const ALPN: &[u8] = b"jaus-link/1";

/// The ring crypto provider (no aws-lc-rs).
pub fn provider() -> Arc<CryptoProvider> {
    Arc::new(rustls::crypto::ring::default_provider())
}

/// The one check both verifiers make: `presented` is `pinned`, with no chain.
fn check(
    pinned: &CertificateDer<'static>,
    presented: &CertificateDer<'_>,
    intermediates: &[CertificateDer<'_>],
    refused: &AtomicU64,
    who: &str,
) -> Result<(), rustls::Error> {
    if presented.as_ref() == pinned.as_ref() && intermediates.is_empty() {
        return Ok(());
    }
    refused.fetch_add(1, Ordering::Relaxed);
    tracing::warn!(
        presented = %crate::keys::fingerprint(presented),
        pinned = %crate::keys::fingerprint(pinned),
        "{who} certificate refused: not the pinned one"
    );
    Err(rustls::Error::InvalidCertificate(
        CertificateError::ApplicationVerificationFailure,
    ))
}

/// TLS 1.2 is never used on a link.
fn no_tls12() -> Result<HandshakeSignatureValid, rustls::Error> {
    Err(rustls::Error::PeerIncompatible(
        rustls::PeerIncompatible::Tls12NotOffered,
    ))
}

/// The server certificate verifier of the connecting end: only the pinned certificate.
#[derive(Debug)]
pub struct PinnedServer {
    pinned: CertificateDer<'static>,
    algorithms: WebPkiSupportedAlgorithms,
    refused: Arc<AtomicU64>,
}

impl PinnedServer {
    /// Accepts only `pinned`; counts refusals in `refused`.
    pub fn new(pinned: CertificateDer<'static>, refused: Arc<AtomicU64>) -> Self {
        Self {
            pinned,
            algorithms: provider().signature_verification_algorithms,
            refused,
        }
    }
}

impl ServerCertVerifier for PinnedServer {
    fn verify_server_cert(
        &self,
        end_entity: &CertificateDer<'_>,
        intermediates: &[CertificateDer<'_>],
        _server_name: &ServerName<'_>,
        _ocsp_response: &[u8],
        _now: UnixTime,
    ) -> Result<ServerCertVerified, rustls::Error> {
        check(
            &self.pinned,
            end_entity,
            intermediates,
            &self.refused,
            "server",
        )
        .map(|()| ServerCertVerified::assertion())
    }

    fn verify_tls12_signature(
        &self,
        _message: &[u8],
        _cert: &CertificateDer<'_>,
        _dss: &DigitallySignedStruct,
    ) -> Result<HandshakeSignatureValid, rustls::Error> {
        no_tls12()
    }

    fn verify_tls13_signature(
        &self,
        message: &[u8],
        cert: &CertificateDer<'_>,
        dss: &DigitallySignedStruct,
    ) -> Result<HandshakeSignatureValid, rustls::Error> {
        rustls::crypto::verify_tls13_signature(message, cert, dss, &self.algorithms)
    }

    fn supported_verify_schemes(&self) -> Vec<SignatureScheme> {
        self.algorithms.supported_schemes()
    }
}

/// The client certificate verifier of the accepting end: a client certificate is
/// required, and only the pinned one is accepted.
#[derive(Debug)]
pub struct PinnedClient {
    pinned: CertificateDer<'static>,
    algorithms: WebPkiSupportedAlgorithms,
    refused: Arc<AtomicU64>,
}

impl PinnedClient {
    /// Accepts only `pinned`; counts refusals in `refused`.
    pub fn new(pinned: CertificateDer<'static>, refused: Arc<AtomicU64>) -> Self {
        Self {
            pinned,
            algorithms: provider().signature_verification_algorithms,
            refused,
        }
    }
}

impl ClientCertVerifier for PinnedClient {
    fn offer_client_auth(&self) -> bool {
        true
    }

    fn client_auth_mandatory(&self) -> bool {
        true
    }

    fn root_hint_subjects(&self) -> &[DistinguishedName] {
        &[]
    }

    fn verify_client_cert(
        &self,
        end_entity: &CertificateDer<'_>,
        intermediates: &[CertificateDer<'_>],
        _now: UnixTime,
    ) -> Result<ClientCertVerified, rustls::Error> {
        check(
            &self.pinned,
            end_entity,
            intermediates,
            &self.refused,
            "client",
        )
        .map(|()| ClientCertVerified::assertion())
    }

    fn verify_tls12_signature(
        &self,
        _message: &[u8],
        _cert: &CertificateDer<'_>,
        _dss: &DigitallySignedStruct,
    ) -> Result<HandshakeSignatureValid, rustls::Error> {
        no_tls12()
    }

    fn verify_tls13_signature(
        &self,
        message: &[u8],
        cert: &CertificateDer<'_>,
        dss: &DigitallySignedStruct,
    ) -> Result<HandshakeSignatureValid, rustls::Error> {
        rustls::crypto::verify_tls13_signature(message, cert, dss, &self.algorithms)
    }

    fn supported_verify_schemes(&self) -> Vec<SignatureScheme> {
        self.algorithms.supported_schemes()
    }
}

/// The TLS configuration of the connecting end: TLS 1.3 only, presenting `identity`,
/// accepting only the server certificate `peer`. Fails when the key is not the
/// certificate's or cannot be used.
pub fn client_config(
    identity: &Identity,
    peer: &CertificateDer<'static>,
    refused: Arc<AtomicU64>,
) -> Result<rustls::ClientConfig, rustls::Error> {
    let mut c = rustls::ClientConfig::builder_with_provider(provider())
        .with_protocol_versions(&[&rustls::version::TLS13])?
        .dangerous()
        .with_custom_certificate_verifier(Arc::new(PinnedServer::new(peer.clone(), refused)))
        .with_client_auth_cert(vec![identity.cert.clone()], identity.key.clone_key())?;
    c.alpn_protocols = vec![ALPN.to_vec()];
    Ok(c)
}

/// The TLS configuration of the accepting end: TLS 1.3 only, presenting `identity`,
/// requiring the client certificate `peer` and no other.
pub fn server_config(
    identity: &Identity,
    peer: &CertificateDer<'static>,
    refused: Arc<AtomicU64>,
) -> Result<rustls::ServerConfig, rustls::Error> {
    let mut c = rustls::ServerConfig::builder_with_provider(provider())
        .with_protocol_versions(&[&rustls::version::TLS13])?
        .with_client_cert_verifier(Arc::new(PinnedClient::new(peer.clone(), refused)))
        .with_single_cert(vec![identity.cert.clone()], identity.key.clone_key())?;
    c.alpn_protocols = vec![ALPN.to_vec()];
    Ok(c)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_the_pinned_certificate_passes_and_refusals_are_counted() {
        let (a, b) = (
            Identity::generate("a").unwrap(),
            Identity::generate("b").unwrap(),
        );
        let refused = Arc::new(AtomicU64::new(0));
        let server = PinnedServer::new(a.cert.clone(), refused.clone());
        let name = ServerName::try_from("anything").unwrap();
        let now = UnixTime::now();
        assert!(server
            .verify_server_cert(&a.cert, &[], &name, &[], now)
            .is_ok());
        assert!(server
            .verify_server_cert(&b.cert, &[], &name, &[], now)
            .is_err());
        // The pinned certificate with a chain after it: not what was pinned.
        assert!(server
            .verify_server_cert(&a.cert, std::slice::from_ref(&b.cert), &name, &[], now)
            .is_err());
        let client = PinnedClient::new(b.cert.clone(), refused.clone());
        assert!(client.client_auth_mandatory());
        assert!(client.verify_client_cert(&b.cert, &[], now).is_ok());
        assert!(client.verify_client_cert(&a.cert, &[], now).is_err());
        assert_eq!(refused.load(Ordering::Relaxed), 3);
        assert!(server
            .supported_verify_schemes()
            .contains(&SignatureScheme::ECDSA_NISTP256_SHA256));
    }

    #[test]
    fn a_key_that_is_not_the_certificates_is_refused() {
        let (a, b) = (
            Identity::generate("a").unwrap(),
            Identity::generate("b").unwrap(),
        );
        let mixed = Identity {
            cert: a.cert.clone(),
            key: b.key.clone_key(),
        };
        let refused = Arc::new(AtomicU64::new(0));
        assert!(client_config(&mixed, &b.cert, refused.clone()).is_err());
        assert!(server_config(&mixed, &b.cert, refused.clone()).is_err());
        let c = client_config(&a, &b.cert, refused.clone()).unwrap();
        assert_eq!(c.alpn_protocols, [ALPN.to_vec()]);
        assert!(server_config(&a, &b.cert, refused).is_ok());
    }
}
