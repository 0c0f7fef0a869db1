//! `GET /api/live`: a WebSocket (RFC 6455) carrying `/api/solve`, so that dragging a slider
//! costs one small message each way instead of a whole HTTP request.
//!
//! The page sends each solve's request as one text message, the JSON body it would POST to
//! `/api/solve`; the server answers each, in order, with one text message
//! `{"status": STATUS, "answer": ANSWER}`, the status and JSON body of that POST. Nothing else
//! is carried: the other APIs stay plain POSTs.
//!
//! In a browser a fetch is a request built, checked and sent by the network process and a
//! response handed back through it, several tasks on the page's busy main thread each way: on
//! the Jansen leg, 1.5 to 2 ms before the request left the page and as much again after the
//! answer was back. A message on an open socket is one task each way.
//!
//! The upgrade is checked by the server (`mod.rs`) as any request is (the loopback `Host`),
//! and also its `Origin`, since a browser lets any page open a WebSocket to any address: only
//! the server's own page (or a client that is not a browser, which sends none) may. A message
//! over [`MAX_BODY`](super::MAX_BODY), a binary message or a frame that breaks the protocol
//! closes the socket with the status the RFC gives; the server goes on.
//!
//! The protocol (framing, masking, fragments, pings, the closing handshake) is tungstenite's;
//! this module chooses what is refused and answers the messages.

use std::io::{Read, Write};
use tungstenite::error::{CapacityError, Error};
use tungstenite::protocol::frame::coding::CloseCode;
use tungstenite::protocol::{CloseFrame, Role, WebSocket, WebSocketConfig};
use tungstenite::Message;

/// The WebSocket's path.
pub const PATH: &str = "/api/live";

/// The live sockets open at once, at most: each has its own thread.
pub const MAX_SOCKETS: usize = 8;

/// The `Sec-WebSocket-Accept` that answers a client's `Sec-WebSocket-Key` (RFC 6455, 4.2.2).
pub fn accept_key(key: &str) -> String {
    tungstenite::handshake::derive_accept_key(key.trim().as_bytes())
}

/// Whether `key` is a `Sec-WebSocket-Key`: 16 bytes in base64.
pub fn valid_key(key: &str) -> bool {
    let key = key.trim();
    key.len() == 24
        && key.ends_with("==")
        && key[..22]
            .bytes()
            .all(|b| b.is_ascii_alphanumeric() || b == b'+' || b == b'/')
}

/// Serves the messages of one socket, messages and frames of at most `max` bytes, until it
/// closes: each text message is answered with `answer`'s text.
pub fn serve<S: Read + Write>(stream: S, max: usize, mut answer: impl FnMut(&[u8]) -> String) {
    let config = WebSocketConfig::default()
        .max_message_size(Some(max))
        .max_frame_size(Some(max));
    let mut socket = WebSocket::from_raw_socket(stream, Role::Server, Some(config));
    let (code, why, rest) = loop {
        match socket.read() {
            Ok(Message::Text(text)) => {
                if socket.send(Message::text(answer(text.as_bytes()))).is_err() {
                    return;
                }
            }
            Ok(Message::Binary(_)) => {
                break (CloseCode::Unsupported, "binary messages are not read", 0)
            }
            // Pings are answered and the client's close returned by the socket itself.
            Ok(_) => {}
            Err(Error::Capacity(CapacityError::MessageTooLong { size, .. })) => {
                break (CloseCode::Size, "a message over the limit", size)
            }
            Err(Error::Utf8(_)) => break (CloseCode::Invalid, "a text message not UTF-8", 0),
            Err(Error::Protocol(_) | Error::Capacity(_)) => {
                break (CloseCode::Protocol, "a frame against RFC 6455", 0)
            }
            // Closed, or the client gone: the connection ends.
            Err(_) => return,
        }
    };
    // A message refused: the close sent, then what the client sends until it closes read and
    // dropped (at most the refused frame and a mebibyte), so that it reads the close before
    // the connection ends rather than a reset.
    let close = CloseFrame {
        code,
        reason: why.into(),
    };
    if socket
        .close(Some(close))
        .and_then(|()| socket.flush())
        .is_ok()
    {
        drain(socket.get_mut(), rest.saturating_add(1 << 20));
    }
}

/// Reads and drops up to `limit` bytes of `stream`, until it ends.
fn drain(stream: &mut impl Read, mut limit: usize) {
    let mut buf = [0u8; 8192];
    while limit > 0 {
        match stream.read(&mut buf) {
            Ok(0) | Err(_) => return,
            Ok(n) => limit = limit.saturating_sub(n),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io;

    const OP_CONTINUATION: u8 = 0x0;
    const OP_TEXT: u8 = 0x1;
    const OP_BINARY: u8 = 0x2;
    const OP_CLOSE: u8 = 0x8;
    const OP_PING: u8 = 0x9;
    const OP_PONG: u8 = 0xA;

    #[test]
    fn the_handshake_answers_the_rfcs_example() {
        assert!(valid_key("dGhlIHNhbXBsZSBub25jZQ=="));
        assert_eq!(
            accept_key("dGhlIHNhbXBsZSBub25jZQ=="),
            "s3pPLMBiTxaQ9kYGzzhZRbK+xOo="
        );
        assert!(!valid_key("dGhlIHNhbXBsZSBub25jZQ"));
        assert!(!valid_key("dGhlIHNhbXBsZSBub25j!Q=="));
    }

    /// A client's frame: masked, as a browser sends it.
    fn frame(fin: bool, opcode: u8, payload: &[u8]) -> Vec<u8> {
        let mask = [0x37, 0xfa, 0x21, 0x3d];
        let mut f = vec![if fin { 0x80 } else { 0 } | opcode];
        match payload.len() {
            n if n < 126 => f.push(0x80 | n as u8),
            n if n <= 0xFFFF => {
                f.push(0x80 | 126);
                f.extend_from_slice(&(n as u16).to_be_bytes());
            }
            n => {
                f.push(0x80 | 127);
                f.extend_from_slice(&(n as u64).to_be_bytes());
            }
        }
        f.extend_from_slice(&mask);
        f.extend(payload.iter().enumerate().map(|(k, b)| b ^ mask[k % 4]));
        f
    }

    /// A client's bytes in, the server's bytes out.
    #[derive(Debug)]
    struct Wire {
        input: io::Cursor<Vec<u8>>,
        output: Vec<u8>,
    }

    impl Read for Wire {
        fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
            self.input.read(buf)
        }
    }

    impl Write for Wire {
        fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
            self.output.write(buf)
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    /// The server's frames, as (opcode, payload).
    fn frames(mut bytes: &[u8]) -> Vec<(u8, Vec<u8>)> {
        let mut out = Vec::new();
        while !bytes.is_empty() {
            let opcode = bytes[0] & 0x0F;
            assert_eq!(bytes[1] & 0x80, 0, "a server's frame is not masked");
            let (len, at) = match bytes[1] {
                126 => (usize::from(u16::from_be_bytes([bytes[2], bytes[3]])), 4),
                127 => {
                    let mut b = [0u8; 8];
                    b.copy_from_slice(&bytes[2..10]);
                    (u64::from_be_bytes(b) as usize, 10)
                }
                n => (usize::from(n), 2),
            };
            out.push((opcode, bytes[at..at + len].to_vec()));
            bytes = &bytes[at + len..];
        }
        out
    }

    fn run(input: Vec<u8>, max: usize) -> Vec<(u8, Vec<u8>)> {
        let mut wire = Wire {
            input: io::Cursor::new(input),
            output: Vec::new(),
        };
        serve(&mut wire, max, |m| {
            format!("answer to {}", String::from_utf8_lossy(m))
        });
        frames(&wire.output)
    }

    #[test]
    fn each_message_is_answered_in_order_and_pings_on_the_way() {
        let long = "x".repeat(70_000);
        let mut input = frame(true, OP_TEXT, b"one");
        input.extend(frame(false, OP_TEXT, b"t"));
        input.extend(frame(true, OP_PING, b"hi"));
        input.extend(frame(true, OP_CONTINUATION, b"wo"));
        input.extend(frame(true, OP_TEXT, long.as_bytes()));
        input.extend(frame(true, OP_CLOSE, &1000u16.to_be_bytes()));
        let out = run(input, 1 << 20);
        assert_eq!(out.len(), 5, "{out:?}");
        assert_eq!(out[0], (OP_TEXT, b"answer to one".to_vec()));
        assert_eq!(out[1], (OP_PONG, b"hi".to_vec()));
        assert_eq!(out[2], (OP_TEXT, b"answer to two".to_vec()));
        assert_eq!(out[3].1.len(), "answer to ".len() + long.len());
        assert_eq!(out[4], (OP_CLOSE, 1000u16.to_be_bytes().to_vec()));
    }

    #[test]
    fn a_broken_or_too_large_message_closes_the_socket_with_its_status() {
        let status = |out: &[(u8, Vec<u8>)]| {
            let (op, payload) = out.last().expect("a close");
            assert_eq!(*op, OP_CLOSE);
            u16::from_be_bytes([payload[0], payload[1]])
        };
        // Over the cap: refused from the frame's head, before its payload is read.
        let mut big = frame(true, OP_TEXT, &[b'a'; 200]);
        big.truncate(20);
        assert_eq!(status(&run(big, 100)), 1009);
        // Fragments adding up to over the cap.
        let mut parts = frame(false, OP_TEXT, &[b'a'; 60]);
        parts.extend(frame(true, OP_CONTINUATION, &[b'a'; 60]));
        assert_eq!(status(&run(parts, 100)), 1009);
        assert_eq!(status(&run(frame(true, OP_BINARY, b"\x00"), 100)), 1003);
        assert_eq!(status(&run(frame(true, OP_TEXT, b"\xff\xfe"), 100)), 1007);
        assert_eq!(status(&run(frame(true, OP_CONTINUATION, b"a"), 100)), 1002);
        let mut unmasked = frame(true, OP_TEXT, b"a");
        unmasked[1] &= 0x7F;
        assert_eq!(status(&run(unmasked, 100)), 1002);
        assert_eq!(status(&run(frame(false, OP_PING, b"a"), 100)), 1002);
        // A client gone mid-frame: the socket ends without a word.
        let mut cut = frame(true, OP_TEXT, b"hello");
        cut.truncate(8);
        assert!(run(cut, 100).is_empty());
    }
}
