//! A Kinco RS-232 line whose far end is the simulator's RS-232 server, in process: each request
//! telegram goes through the same sans-I/O exchange a serial client uses, and the server's bytes
//! come back. The test double and example line of applications using `drivebus::rs232`.

use drivebus::rs232::data::{Answer, Request};
use drivebus::rs232::exchange::Exchange;
use drivebus::rs232::{LoopMode, StationId, TelegramBus};
use drivebus::BusError;

use super::Rs232Server;

/// The line to one simulated drive (point to point).
#[derive(Debug)]
pub struct InProcessLine {
    server: Rs232Server,
}

impl InProcessLine {
    /// A line to `server`.
    pub fn new(server: Rs232Server) -> Self {
        Self { server }
    }
}

impl TelegramBus for InProcessLine {
    fn exchange(&mut self, station: StationId, request: &Request) -> Result<Answer, BusError> {
        let object = request.object();
        let mut exchange = Exchange::new(station, *request, LoopMode::PointToPoint);
        let reply = self.server.handle(exchange.telegram());
        match exchange.receive(&reply) {
            Ok(Some(answer)) => Ok(answer),
            Ok(None) => Err(exchange.timed_out().about(object)),
            Err(error) => Err(error.about(object)),
        }
    }
}
