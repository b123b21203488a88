//! The Communicator: over the UDP links of its entry, or over links the caller made.

use super::build::{BuildCx, Built};
use super::{Entry, Host, HostError};
use jaus::component::{Config, Endpoint};
use jaus::net::udp::link::UdpLink;
use jaus::stock::communicator::{
    CommunicatorConfig, CommunicatorEndpoint, CommunicatorError, DataLink, StockCommunicator,
};
use jaus::Address;

impl Host {
    /// A Communicator with the instance and authority of `e` (an entry of the
    /// `communicator` [`Stock`](super::Stock)) over `links` that the caller made (any
    /// [`DataLink`]: a link of its own hardware, a QUIC link, `Box<dyn DataLink>` for
    /// a mix), all On, the first selected; `e.links` is not used. The UDP links of
    /// `e.links` are what [`Host::build`] makes itself.
    pub fn build_communicator<L: DataLink>(
        &mut self,
        e: &Entry,
        links: Vec<L>,
    ) -> Result<Box<dyn Endpoint>, HostError> {
        let e = match super::Stock::by_id(jaus::components::communicator::ID) {
            Some(stock) => Entry { stock, ..e.clone() },
            None => e.clone(),
        };
        let at = self.address_of(&e)?;
        let built = communicator_over(self, at, &e, links)?;
        self.built.push(at);
        Ok(built)
    }
}

/// The Communicator of `e` at `at` over `links`, all On, the first selected.
fn communicator_over<L: DataLink>(
    host: &Host,
    at: Address,
    e: &Entry,
    links: Vec<L>,
) -> Result<Box<dyn Endpoint>, HostError> {
    let component = e.stock.name();
    let stock = StockCommunicator::new(links, CommunicatorConfig::default(), host.t0)
        .map_err(|error| HostError::Links { component, error })?;
    let cfg = Config {
        authority: e.authority,
        ..Config::default()
    };
    Ok(Box::new(CommunicatorEndpoint::new(at, stock, cfg, host.t0)))
}

impl BuildCx<'_> {
    /// The Communicator of the entry: its UDP links bound, all On, the first selected.
    pub(super) fn communicator(&self) -> Built {
        let e = self.links();
        let component = e.stock.name();
        // Checked before any socket is bound (StockCommunicator::new checks again).
        let ids: Vec<u8> = e.links.iter().map(|l| l.id).collect();
        let error = if ids.is_empty() {
            Some(CommunicatorError::NoLinks)
        } else {
            (1..ids.len())
                .find(|&i| ids[..i].contains(&ids[i]))
                .map(|i| CommunicatorError::DuplicateId(ids[i]))
        };
        if let Some(error) = error {
            return Err(HostError::Links { component, error });
        }
        let links = e
            .links
            .iter()
            .map(|l| {
                UdpLink::bind(l.clone()).map_err(|err| HostError::Link {
                    component,
                    link: l.id,
                    error: err.to_string(),
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        communicator_over(self.host(), self.at, e, links)
    }
}
