//! Checks made on every request before any route sees it, so that only the user's own browser
//! tab gets answers ([`check`]):
//!
//! | check | refused with |
//! | --- | --- |
//! | `Host` names this server ([`Access`]): `localhost`, `127.0.0.1` or `[::1]` with the server's port, or the address given with `--host` | 403 |
//! | `Origin`, when sent, is the server's own origin `http://HOST` | 403 |
//! | a POST body is `Content-Type: application/json` | 415 |
//! | a POST body is at most [`MAX_BODY_BYTES`] | 413 |
//! | a POST body arrives within [`BODY_TIMEOUT`] | 408 |
//!
//! Why: a page on another site may POST `text/plain` to a local server without a CORS
//! preflight (the JSON and Origin checks refuse it), and a DNS-rebinding page reaches the
//! server under its own host name (the Host check refuses it). Every refusal is
//! `{"error": "..."}`, like the API's other errors.

use std::net::{IpAddr, Ipv4Addr, Ipv6Addr, SocketAddr};
use std::sync::Arc;

use axum::body::Body;
use axum::extract::{Request, State};
use axum::http::{header, HeaderMap, Method, StatusCode};
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};

use crate::api_error::ApiError;

/// Largest request body read (4 MiB: the settings of a few thousand objects).
pub const MAX_BODY_BYTES: usize = 4 << 20;

/// Longest wait for a request body: a client that sends its body slowly or never does not
/// hold its connection (and a place under the connection cap) for long.
pub const BODY_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(30);

/// The host names a local server always answers to.
const LOCAL_NAMES: [&str; 3] = ["localhost", "127.0.0.1", "[::1]"];

/// Which `Host` values name this server.
#[derive(Clone, Debug)]
pub struct Access {
    port: u16,
    /// Further names (lowercase, IPv6 in brackets) besides [`LOCAL_NAMES`].
    names: Vec<String>,
    /// Any IP address literal (a server listening on every interface, reached by address).
    any_address: bool,
}

impl Access {
    /// This machine only: `localhost`, `127.0.0.1` or `[::1]` with `port`.
    pub fn local(port: u16) -> Access {
        Access {
            port,
            names: Vec::new(),
            any_address: false,
        }
    }

    /// For a server listening on `addr`: the localhost names and that address; listening on
    /// every interface (`0.0.0.0`, `::`) accepts any IP address (names other than
    /// `localhost` stay refused, against DNS rebinding).
    pub fn listening_on(addr: SocketAddr) -> Access {
        let mut access = Access::local(addr.port());
        match addr.ip() {
            ip if ip.is_unspecified() => access.any_address = true,
            IpAddr::V4(ip) => access.names.push(ip.to_string()),
            IpAddr::V6(ip) => access.names.push(format!("[{ip}]")),
        }
        access
    }

    /// Whether a `Host` header value names this server.
    pub fn allows_host(&self, host: &str) -> bool {
        let Some((name, port)) = split_host(host) else {
            return false;
        };
        let port_ok = match port {
            Some(p) => p.parse::<u16>() == Ok(self.port),
            None => self.port == 80,
        };
        let name = name.to_ascii_lowercase();
        let name_ok = LOCAL_NAMES.contains(&name.as_str())
            || self.names.contains(&name)
            || (self.any_address && is_address(&name));
        port_ok && name_ok
    }

    /// What a refused request is told to use instead.
    fn hint(&self) -> String {
        format!(
            "this viewer answers requests to localhost, 127.0.0.1 or [::1] on port {}{} \
             (start godel view with --host to serve another address)",
            self.port,
            if self.any_address {
                " or to one of its IP addresses"
            } else if self.names.iter().all(|n| LOCAL_NAMES.contains(&n.as_str())) {
                ""
            } else {
                " or to the address given with --host"
            }
        )
    }
}

/// (name, port) of a `Host` value: `name`, `name:port`, `[v6]` or `[v6]:port`.
fn split_host(host: &str) -> Option<(&str, Option<&str>)> {
    if host.starts_with('[') {
        let end = host.find(']')? + 1;
        let (name, rest) = host.split_at(end);
        match rest {
            "" => Some((name, None)),
            _ => Some((name, Some(rest.strip_prefix(':')?))),
        }
    } else {
        Some(match host.rsplit_once(':') {
            Some((name, port)) => (name, Some(port)),
            None => (host, None),
        })
    }
}

/// An IPv4 address or a bracketed IPv6 address.
fn is_address(name: &str) -> bool {
    match name.strip_prefix('[').and_then(|n| n.strip_suffix(']')) {
        Some(v6) => v6.parse::<Ipv6Addr>().is_ok(),
        None => name.parse::<Ipv4Addr>().is_ok(),
    }
}

fn header_text(headers: &HeaderMap, name: header::HeaderName) -> Option<&str> {
    headers.get(name).map(|v| v.to_str().unwrap_or("\u{fffd}"))
}

fn forbidden(message: String) -> Response {
    ApiError::new(StatusCode::FORBIDDEN, message).into_response()
}

/// The middleware: refuses what the table in the module documentation refuses; passes the
/// rest on with a POST body already read (within [`MAX_BODY_BYTES`]).
pub async fn check(State(access): State<Arc<Access>>, request: Request, next: Next) -> Response {
    let headers = request.headers();
    let Some(host) = header_text(headers, header::HOST) else {
        return forbidden(format!("the request names no Host; {}", access.hint()));
    };
    if !access.allows_host(host) {
        return forbidden(format!("Host '{host}' is refused: {}", access.hint()));
    }
    if let Some(origin) = header_text(headers, header::ORIGIN) {
        let own = format!("http://{host}");
        if !origin.eq_ignore_ascii_case(&own) {
            return forbidden(format!(
                "requests from other pages are refused (Origin '{origin}', this viewer is {own})"
            ));
        }
    }
    if request.method() != Method::POST {
        return next.run(request).await;
    }
    let json = header_text(headers, header::CONTENT_TYPE)
        .and_then(|t| t.split(';').next())
        .is_some_and(|t| t.trim().eq_ignore_ascii_case("application/json"));
    if !json {
        return ApiError::new(
            StatusCode::UNSUPPORTED_MEDIA_TYPE,
            "settings must be sent as Content-Type: application/json",
        )
        .into_response();
    }
    let too_large = || {
        ApiError::new(
            StatusCode::PAYLOAD_TOO_LARGE,
            format!(
                "the request body is larger than {} MiB",
                MAX_BODY_BYTES >> 20
            ),
        )
        .into_response()
    };
    let declared = header_text(headers, header::CONTENT_LENGTH).and_then(|l| l.parse::<u64>().ok());
    if declared.is_some_and(|l| l > MAX_BODY_BYTES as u64) {
        return too_large();
    }
    let (parts, body) = request.into_parts();
    let read = tokio::time::timeout(BODY_TIMEOUT, axum::body::to_bytes(body, MAX_BODY_BYTES));
    let Ok(read) = read.await else {
        return ApiError::new(
            StatusCode::REQUEST_TIMEOUT,
            format!(
                "the request body did not arrive within {} s",
                BODY_TIMEOUT.as_secs()
            ),
        )
        .into_response();
    };
    let bytes = match read {
        Ok(b) => b,
        Err(e) => {
            let inner = e.into_inner();
            if inner
                .downcast_ref::<http_body_util::LengthLimitError>()
                .is_some()
            {
                return too_large();
            }
            return ApiError::bad_request(format!("reading the request body: {inner}"))
                .into_response();
        }
    };
    next.run(Request::from_parts(parts, Body::from(bytes)))
        .await
}
