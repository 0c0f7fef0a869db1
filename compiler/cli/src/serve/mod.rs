//! `gcs serve FILE`: a local page where the model is edited, checked, solved and drawn as its
//! params move.
//!
//! The server (tiny_http, one request at a time) answers only:
//!
//! - `GET /`, `/style.css`, `/app.js`: the page, embedded in the binary (`page/`);
//! - `GET /api/model`: the file's name and its text, read from disk at each request (the
//!   only file the server reads; it writes none);
//! - `POST /api/check`, `/api/solve`, `/api/compile`: the JSON API of [`api`], whose
//!   requests carry the editor's text;
//! - `GET /api/live`: a WebSocket carrying `/api/solve`'s requests and answers ([`live`]), what
//!   the page solves on while a slider is dragged; each socket has its own thread, and the API
//!   answers one request at a time, whichever connection asked.
//!
//! Anything else is a 404 (no path is ever mapped to a file), a body or message over
//! [`MAX_BODY`] a 413 (a socket closed with 1009), and a request whose `Host` is not the
//! loopback address the server is bound to a 403 (a page elsewhere cannot reach it through a
//! name of its own), as is a WebSocket opened by a page of another origin. A model that does
//! not parse, analyse or solve is an answer like any other, and a panic while answering (a bug
//! in gcs) is a 500: the server goes on.

pub mod api;
pub mod live;

use std::io::{Read as _, Write as _};
use std::net::{IpAddr, SocketAddr};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use tiny_http::{Header, Method, Response, Server};

/// The largest request body read, in bytes: a model's text with room to spare.
pub const MAX_BODY: usize = 1 << 20;

/// The page, as files kept beside this module and embedded at build time.
const INDEX_HTML: &str = include_str!("page/index.html");
const STYLE_CSS: &str = include_str!("page/style.css");
const APP_JS: &str = include_str!("page/app.js");

/// Serves the model at `path` on `host:port` (port 0: a free one) until the process is
/// stopped. The first line on standard output is the page's URL.
pub fn run(path: &Path, host: &str, port: u16) -> ExitCode {
    let name = path.display().to_string();
    if let Err(e) = std::fs::read(path) {
        eprintln!("error: cannot read `{name}`: {e}");
        return ExitCode::from(2);
    }
    let ip: IpAddr = match host.parse() {
        Ok(ip) => ip,
        Err(_) if host == "localhost" => IpAddr::from([127, 0, 0, 1]),
        Err(_) => {
            eprintln!("error: `--host {host}`: not an IP address (127.0.0.1, ::1, 0.0.0.0)");
            return ExitCode::from(2);
        }
    };
    let server = match listen(SocketAddr::new(ip, port)) {
        Ok(s) => s,
        Err(e) => {
            eprintln!("error: cannot listen on {host}:{port}: {e}");
            return ExitCode::from(2);
        }
    };
    let Some(bound) = server.server_addr().to_ip() else {
        eprintln!("error: the server has no IP address");
        return ExitCode::from(2);
    };
    let url = match bound {
        SocketAddr::V4(a) => format!("http://{}:{}/", a.ip(), a.port()),
        SocketAddr::V6(a) => format!("http://[{}]:{}/", a.ip(), a.port()),
    };
    outln!("{url}");
    eprintln!("serving `{name}` at {url} (Ctrl-C stops)");
    let _ = std::io::stdout().flush();
    let shared = Arc::new(Shared {
        api: Mutex::new(api::Api::new(name)),
        path: path.to_path_buf(),
        live: AtomicUsize::new(0),
    });
    for mut request in server.incoming_requests() {
        if route(&request) == live::PATH && *request.method() == Method::Get {
            match upgrade(&shared, bound, &request) {
                Ok(accept) => go_live(&shared, request, &accept),
                Err(reply) => respond(request, reply),
            }
            continue;
        }
        let reply = answer(&shared, bound, &mut request);
        respond(request, reply);
    }
    ExitCode::SUCCESS
}

/// Sends `reply` as the response to `request`.
fn respond(request: tiny_http::Request, reply: Reply) {
    let mut response = Response::from_data(reply.body).with_status_code(reply.status);
    let allow = (reply.status == 405).then_some(("Allow", "GET, POST"));
    let upgrade = (reply.status == 426).then_some(("Upgrade", "websocket"));
    let headers = [
        ("Content-Type", reply.content_type),
        ("Cache-Control", "no-store"),
        ("X-Content-Type-Options", "nosniff"),
    ];
    for (name, value) in headers.into_iter().chain(allow).chain(upgrade) {
        if let Ok(h) = Header::from_bytes(name.as_bytes(), value.as_bytes()) {
            response.add_header(h);
        }
    }
    // A client that went away is no reason to stop.
    let _ = request.respond(response);
}

/// What every connection shares: the API of the model (one answer at a time), its path, and
/// how many live sockets are open.
#[derive(Debug)]
struct Shared {
    api: Mutex<api::Api>,
    path: PathBuf,
    live: AtomicUsize,
}

impl Shared {
    /// The API's answer to a POST of `body` to `route`. A panic is a bug in gcs: the request
    /// fails (a 500), the server goes on, with the model compiled again at the next request.
    fn answer(&self, route: &str, body: &[u8]) -> api::Answer {
        let mut api = self.api.lock().unwrap_or_else(|e| e.into_inner());
        let answered =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| api.answer(route, body)));
        answered.unwrap_or_else(|_| {
            *api = api::Api::new(self.path.display().to_string());
            api::Answer {
                status: 500,
                body: serde_json::json!({
                    "ok": false,
                    "error": "internal error: gcs panicked (a bug in gcs: please report it)",
                }),
            }
        })
    }
}

/// The request's path, without its query or fragment.
fn route(request: &tiny_http::Request) -> &str {
    let url = request.url();
    url.split(['?', '#']).next().unwrap_or(url)
}

/// The value of the request's header `name`, if it has one.
fn header<'r>(request: &'r tiny_http::Request, name: &'static str) -> Option<&'r str> {
    (request.headers().iter())
        .find(|h| h.field.equiv(name))
        .map(|h| h.value.as_str())
}

/// Whether a `GET /api/live` may become a live socket: the loopback `Host`, an `Origin` that is
/// this server's own (a browser lets any page open a WebSocket anywhere; a client that is not a
/// browser sends none), a WebSocket handshake of version 13, and a socket free. The
/// `Sec-WebSocket-Accept` to answer with; else the reply refusing it.
fn upgrade(
    shared: &Shared,
    bound: SocketAddr,
    request: &tiny_http::Request,
) -> Result<String, Reply> {
    if !host_allowed(bound, request) {
        return Err(Reply::error(
            403,
            "this server answers only at its own loopback address",
        ));
    }
    let host = header(request, "Host").unwrap_or("").to_ascii_lowercase();
    let own =
        |origin: &str| !host.is_empty() && origin.to_ascii_lowercase() == format!("http://{host}");
    if header(request, "Origin").is_some_and(|o| !own(o)) {
        return Err(Reply::error(
            403,
            "only this server's own page may open its live socket",
        ));
    }
    let has = |name: &'static str, token: &str| {
        header(request, name)
            .is_some_and(|v| v.split(',').any(|t| t.trim().eq_ignore_ascii_case(token)))
    };
    if !has("Upgrade", "websocket") || !has("Connection", "upgrade") {
        return Err(Reply::error(
            426,
            "this is a WebSocket (Upgrade: websocket)",
        ));
    }
    if header(request, "Sec-WebSocket-Version").map(str::trim) != Some("13") {
        return Err(Reply::error(426, "this WebSocket speaks version 13"));
    }
    let Some(key) = header(request, "Sec-WebSocket-Key").filter(|k| live::valid_key(k)) else {
        return Err(Reply::error(400, "no Sec-WebSocket-Key, or not one"));
    };
    if shared.live.load(Ordering::SeqCst) >= live::MAX_SOCKETS {
        return Err(Reply::error(503, "too many live sockets are open"));
    }
    Ok(live::accept_key(key))
}

/// Turns `request` into a live socket served on its own thread: each message a solve's
/// request, each answered with `{"status", "answer"}`, `/api/solve`'s status and JSON.
fn go_live(shared: &Arc<Shared>, request: tiny_http::Request, accept: &str) {
    let mut response = Response::empty(101);
    if let Ok(h) = Header::from_bytes(&b"Sec-WebSocket-Accept"[..], accept.as_bytes()) {
        response.add_header(h);
    }
    let stream = request.upgrade("websocket", response);
    /// One of the open sockets, counted while its thread runs.
    struct Slot(Arc<Shared>);
    impl Drop for Slot {
        fn drop(&mut self) {
            self.0.live.fetch_sub(1, Ordering::SeqCst);
        }
    }
    shared.live.fetch_add(1, Ordering::SeqCst);
    let slot = Slot(Arc::clone(shared));
    // A thread that cannot start drops the socket (and its slot): the page falls back to POSTs.
    let _ = std::thread::Builder::new()
        .name("gcs-serve-live".to_string())
        .spawn(move || {
            let shared = &slot.0;
            live::serve(stream, MAX_BODY, |message| {
                let a = shared.answer("/api/solve", message);
                serde_json::json!({ "status": a.status, "answer": a.body }).to_string()
            });
        });
}

/// The server, listening on `addr` with Nagle's algorithm off on every connection (Linux
/// passes the listener's `TCP_NODELAY` to the connections it accepts): tiny_http writes a
/// response's head and body apart, and on a kept-alive connection Nagle held the body until the
/// client acknowledged the head, which it delays: 40 ms of every answer (1.6 ms without).
fn listen(addr: SocketAddr) -> Result<Server, Box<dyn std::error::Error + Send + Sync>> {
    use socket2::{Domain, Socket, Type};
    let socket = Socket::new(Domain::for_address(addr), Type::STREAM, None)?;
    socket.set_reuse_address(true)?;
    socket.set_tcp_nodelay(true)?;
    socket.bind(&addr.into())?;
    socket.listen(128)?;
    Server::from_listener(std::net::TcpListener::from(socket), None)
}

/// A response: status, content type and body.
struct Reply {
    status: u16,
    content_type: &'static str,
    body: Vec<u8>,
}

impl Reply {
    fn json(status: u16, body: &serde_json::Value) -> Reply {
        Reply {
            status,
            content_type: "application/json",
            body: body.to_string().into_bytes(),
        }
    }

    fn error(status: u16, why: &str) -> Reply {
        Reply::json(status, &serde_json::json!({ "ok": false, "error": why }))
    }

    fn page(content_type: &'static str, text: &'static str) -> Reply {
        Reply {
            status: 200,
            content_type,
            body: text.as_bytes().to_vec(),
        }
    }
}

/// The reply to one request.
fn answer(shared: &Shared, bound: SocketAddr, request: &mut tiny_http::Request) -> Reply {
    if !host_allowed(bound, request) {
        return Reply::error(403, "this server answers only at its own loopback address");
    }
    let route = route(request).to_string();
    let method = request.method().clone();
    let path = shared.path.as_path();
    match (&method, route.as_str()) {
        (Method::Get | Method::Head, "/" | "/index.html") => {
            Reply::page("text/html; charset=utf-8", INDEX_HTML)
        }
        (Method::Get | Method::Head, "/style.css") => {
            Reply::page("text/css; charset=utf-8", STYLE_CSS)
        }
        (Method::Get | Method::Head, "/app.js") => {
            Reply::page("text/javascript; charset=utf-8", APP_JS)
        }
        (Method::Get | Method::Head, "/api/model") => match std::fs::read(path) {
            Ok(bytes) => Reply::json(
                200,
                &serde_json::json!({
                    "name": path.display().to_string(),
                    "text": String::from_utf8_lossy(&bytes),
                }),
            ),
            Err(e) => Reply::error(500, &format!("cannot read `{}`: {e}", path.display())),
        },
        (Method::Post, "/api/check" | "/api/solve" | "/api/compile") => {
            let body = match read_body(request) {
                Ok(b) => b,
                Err(reply) => return reply,
            };
            let a = shared.answer(&route, &body);
            Reply::json(a.status, &a.body)
        }
        (_, "/" | "/index.html" | "/style.css" | "/app.js" | "/api/model" | live::PATH) => {
            Reply::error(405, "use GET")
        }
        (_, "/api/check" | "/api/solve" | "/api/compile") => Reply::error(405, "use POST"),
        _ => Reply::error(
            404,
            "not found: this server serves its page and its API only",
        ),
    }
}

/// The request's body, at most [`MAX_BODY`] bytes; else the 413 to answer.
fn read_body(request: &mut tiny_http::Request) -> Result<Vec<u8>, Reply> {
    let too_large = || Reply::error(413, &format!("the request body is over {MAX_BODY} bytes"));
    if request.body_length().is_some_and(|n| n > MAX_BODY) {
        return Err(too_large());
    }
    let mut body = Vec::new();
    let limit = MAX_BODY as u64 + 1;
    match request.as_reader().take(limit).read_to_end(&mut body) {
        Ok(n) if n > MAX_BODY => Err(too_large()),
        Ok(_) => Ok(body),
        Err(e) => Err(Reply::error(400, &format!("cannot read the request: {e}"))),
    }
}

/// Whether the request may be answered: a server bound to a loopback address answers only
/// requests addressed to a loopback name (`127.0.0.1`, `localhost`, `[::1]`), so that a page of
/// another site, whose name was pointed at this machine, cannot read the model through it.
fn host_allowed(bound: SocketAddr, request: &tiny_http::Request) -> bool {
    if !bound.ip().is_loopback() {
        return true;
    }
    let Some(host) = request
        .headers()
        .iter()
        .find(|h| h.field.equiv("Host"))
        .map(|h| h.value.as_str().to_ascii_lowercase())
    else {
        // HTTP/1.0 clients may send none; they cannot have been sent by a browser elsewhere.
        return true;
    };
    let name = match host.strip_prefix('[') {
        Some(v6) => v6.split(']').next().unwrap_or(""),
        None => host.split(':').next().unwrap_or(""),
    };
    name == "localhost"
        || name.ends_with(".localhost")
        || name.parse::<IpAddr>().is_ok_and(|ip| ip.is_loopback())
}
