//! [`Station`] as a System Commander component: its `tick` and the messages addressed to
//! it are the station's, so an operator station is
//! `system_commander::component(address, station, config, now)`.

use super::Station;
use crate::component::Refused;
use crate::components::system_commander::{Ctx, SystemCommander};
use crate::messages::Message;

impl SystemCommander for Station {
    fn tick(&mut self, ctx: &mut Ctx<'_>) {
        Station::tick(self, ctx);
    }

    fn on_other_message(
        &mut self,
        ctx: &mut Ctx<'_>,
        msg: &Message,
    ) -> Result<Option<Message>, Refused> {
        if let Some(source) = ctx.source() {
            self.on_message(ctx.now(), source, msg);
        }
        Ok(None)
    }
}
