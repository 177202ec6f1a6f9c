//! A serial line whose far end is the simulated drive, in process: for examples and tests that
//! want the RS-232 protocol without a pty.

use drivebus::rs232::data::{Answer, Request};
use drivebus::rs232::exchange::Exchange;
use drivebus::rs232::{StationId, TelegramBus};
use drivebus::BusError;

use super::Rs232Server;

/// A [`TelegramBus`] over a [`Rs232Server`]: each request telegram goes through the same
/// sans-I/O exchange a serial host uses, and the server's bytes come back as the line's.
#[derive(Debug)]
pub struct InProcessLine {
    server: Rs232Server,
}

impl InProcessLine {
    /// The line to `server`'s drive.
    pub fn new(server: Rs232Server) -> Self {
        Self { server }
    }
}

impl TelegramBus for InProcessLine {
    fn exchange(&mut self, station: StationId, request: &Request) -> Result<Answer, BusError> {
        let object = request.object();
        let mut exchange = Exchange::new(station, *request, self.server.mode());
        let reply = self.server.handle(exchange.telegram());
        match exchange.receive(&reply) {
            Ok(Some(answer)) => Ok(answer),
            Ok(None) => Err(exchange.timed_out().about(object)),
            Err(error) => Err(error.about(object)),
        }
    }
}

#[cfg(test)]
mod tests {
    use drivebus::rs232::LoopMode;

    use super::*;
    use crate::Simulator;

    const KINCO: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../descriptions/kinco-fd");

    #[test]
    fn a_read_crosses_the_line_in_either_loop_mode_and_another_station_is_silent() {
        let sim = Simulator::load(KINCO).unwrap();
        // 6041h statusword, 2 bytes, as the manual's upload example reads it.
        let statusword = Request::upload(0x6041, 0x00);
        for mode in [LoopMode::PointToPoint, LoopMode::MultiPoint] {
            let mut line = InProcessLine::new(Rs232Server::new(&sim, StationId(1), mode));
            assert!(matches!(
                line.exchange(StationId(1), &statusword),
                Ok(Answer::Uploaded(..))
            ));
            assert!(line.exchange(StationId(2), &statusword).is_err());
        }
    }
}
