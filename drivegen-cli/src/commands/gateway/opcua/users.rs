//! Who may log in and what they may do: the file's users with their passwords (checked by the
//! server's own authenticator) and their right; anonymous sessions read only. A user without the
//! write right sees the variables' `UserAccessLevel` without write, and a write from them is
//! refused with `BadUserAccessDenied` (the node manager logs it).

use std::collections::BTreeMap;

use async_trait::async_trait;
use drivegen::gateway_file::OpcUaRight;
use opcua::crypto::Thumbprint;
use opcua::server::address_space::AccessLevel;
use opcua::server::authenticator::{AuthManager, DefaultAuthenticator, Password, UserToken};
use opcua::server::{ServerEndpoint, ServerUserToken};
use opcua::types::{Error, NodeId, UserTokenPolicy};

/// The users and their rights.
pub struct Users {
    /// Passwords, checked by the server's authenticator; a user's token is its name.
    passwords: DefaultAuthenticator,
    /// The names with the write right.
    writers: Vec<String>,
}

impl Users {
    /// `users` as (name, password, right).
    pub fn new(users: &[(String, String, OpcUaRight)]) -> Self {
        let tokens = users
            .iter()
            .map(|(name, password, _)| (name.clone(), ServerUserToken::user_pass(name, password)))
            .collect::<BTreeMap<_, _>>();
        Self {
            passwords: DefaultAuthenticator::new(tokens),
            writers: users
                .iter()
                .filter(|(_, _, right)| *right == OpcUaRight::Write)
                .map(|(name, _, _)| name.clone())
                .collect(),
        }
    }

    /// Whether the session of `token` may write.
    pub fn may_write(&self, token: &UserToken) -> bool {
        !token.is_anonymous() && self.writers.contains(&token.0)
    }
}

#[async_trait]
impl AuthManager for Users {
    async fn authenticate_anonymous_token(&self, endpoint: &ServerEndpoint) -> Result<(), Error> {
        self.passwords.authenticate_anonymous_token(endpoint).await
    }

    async fn authenticate_username_identity_token(
        &self,
        endpoint: &ServerEndpoint,
        username: &str,
        password: &Password,
    ) -> Result<UserToken, Error> {
        self.passwords
            .authenticate_username_identity_token(endpoint, username, password)
            .await
    }

    async fn authenticate_x509_identity_token(
        &self,
        endpoint: &ServerEndpoint,
        signing_thumbprint: &Thumbprint,
    ) -> Result<UserToken, Error> {
        self.passwords
            .authenticate_x509_identity_token(endpoint, signing_thumbprint)
            .await
    }

    fn effective_user_access_level(
        &self,
        token: &UserToken,
        user_access_level: AccessLevel,
        _node_id: &NodeId,
    ) -> AccessLevel {
        match self.may_write(token) {
            true => user_access_level,
            false => user_access_level - AccessLevel::CURRENT_WRITE,
        }
    }

    fn user_token_policies(&self, endpoint: &ServerEndpoint) -> Vec<UserTokenPolicy> {
        self.passwords.user_token_policies(endpoint)
    }
}
