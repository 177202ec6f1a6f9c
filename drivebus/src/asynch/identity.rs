//! The identity check on connect, awaited: the blocking check's reads over an async link, and
//! its conclusion from each value read ([`Device::conclude_identity`]).

use super::link::{Async, AsyncLink};
use crate::device::Device;
use crate::error::Error;
use crate::identity::IdentityCheck;

impl<L: AsyncLink> Device<Async<L>> {
    /// Reads each identity parameter of `checks` in turn, as the blocking
    /// [`Device::verify_identity`] does: at the first holding a value not covered, refuses
    /// every later write and returns the refusal as [`Error::WritesRefused`].
    pub async fn verify_identity(
        &mut self,
        checks: &[IdentityCheck<L::Protocol>],
    ) -> Result<(), Error> {
        for check in checks {
            let found = self.read_integer(&check.parameter).await?;
            self.conclude_identity(check, found)?;
        }
        Ok(())
    }
}
