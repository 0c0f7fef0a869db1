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

use std::io::{self, Read, Write};

/// The WebSocket's path.
pub const PATH: &str = "/api/live";

/// The live sockets open at once, at most: each has its own thread.
pub const MAX_SOCKETS: usize = 8;

/// The `Sec-WebSocket-Accept` that answers a client's `Sec-WebSocket-Key` (RFC 6455, 4.2.2).
pub fn accept_key(key: &str) -> String {
    const GUID: &str = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11";
    base64(&sha1(format!("{}{GUID}", key.trim()).as_bytes()))
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

/// Serves the messages of one socket until it closes: each text message is answered with
/// `answer`'s text.
pub fn serve<S: Read + Write>(stream: S, max: usize, mut answer: impl FnMut(&[u8]) -> String) {
    let mut socket = Socket { stream };
    let (code, why, rest) = loop {
        match socket.read_message(max) {
            Ok(Some(text)) => {
                if socket.send(OP_TEXT, answer(&text).as_bytes()).is_err() {
                    return;
                }
            }
            // The client closed it: the close answered, the connection ends.
            Ok(None) => return socket.close(1000, ""),
            Err(Failure::Gone) => return,
            // The frames cannot be told apart any more: the connection ends.
            Err(Failure::Broken(code, why)) => return socket.close(code, why),
            Err(Failure::Refused(code, why, rest)) => break (code, why, rest),
        }
    };
    // A message refused: the close sent, then the rest of its frame read and dropped (unless it
    // is far larger than allowed) and the client's frames until its close, as RFC 6455 asks, so
    // that the client reads the close before the connection ends.
    socket.close(code, why);
    if rest <= max as u64 + (1 << 20) && socket.skip(rest).is_ok() {
        socket.linger(max);
    }
}

const OP_CONTINUATION: u8 = 0x0;
const OP_TEXT: u8 = 0x1;
const OP_BINARY: u8 = 0x2;
const OP_CLOSE: u8 = 0x8;
const OP_PING: u8 = 0x9;
const OP_PONG: u8 = 0xA;

/// Why a socket stops: it failed (the client went away: nothing more to say); the client broke
/// the framing (the close status to send, and why); or it sent a message refused (the status,
/// why, and how many bytes of its frame are still to come).
#[derive(Debug)]
enum Failure {
    Gone,
    Broken(u16, &'static str),
    Refused(u16, &'static str, u64),
}

impl From<io::Error> for Failure {
    fn from(_: io::Error) -> Failure {
        Failure::Gone
    }
}

/// A frame from the client, unmasked.
#[derive(Debug)]
struct Frame {
    fin: bool,
    opcode: u8,
    payload: Vec<u8>,
}

/// The server's end of a WebSocket.
#[derive(Debug)]
struct Socket<S> {
    stream: S,
}

impl<S: Read + Write> Socket<S> {
    /// The next frame, whose payload, unless it is a control frame, is at most `room` bytes.
    fn read_frame(&mut self, room: usize) -> Result<Frame, Failure> {
        let mut head = [0u8; 2];
        self.stream.read_exact(&mut head)?;
        let (fin, opcode) = (head[0] & 0x80 != 0, head[0] & 0x0F);
        if head[0] & 0x70 != 0 {
            return Err(Failure::Broken(1002, "no extension was agreed"));
        }
        if head[1] & 0x80 == 0 {
            return Err(Failure::Broken(1002, "a client's frame is masked"));
        }
        let len = match head[1] & 0x7F {
            126 => {
                let mut b = [0u8; 2];
                self.stream.read_exact(&mut b)?;
                u64::from(u16::from_be_bytes(b))
            }
            127 => {
                let mut b = [0u8; 8];
                self.stream.read_exact(&mut b)?;
                u64::from_be_bytes(b)
            }
            n => u64::from(n),
        };
        let control = opcode & 0x8 != 0;
        if control && (!fin || len > 125) {
            return Err(Failure::Broken(1002, "a control frame is short and whole"));
        }
        if !control && len > room as u64 {
            return Err(Failure::Refused(1009, "the message is too large", len + 4));
        }
        let mut mask = [0u8; 4];
        self.stream.read_exact(&mut mask)?;
        // At most `room` (or 125) bytes: the length was checked above.
        let mut payload = vec![0u8; len as usize];
        self.stream.read_exact(&mut payload)?;
        for (k, b) in payload.iter_mut().enumerate() {
            *b ^= mask[k % 4];
        }
        Ok(Frame {
            fin,
            opcode,
            payload,
        })
    }

    /// The next text message, its fragments joined, at most `max` bytes; pings are answered on
    /// the way. `None`: the client closed the socket.
    fn read_message(&mut self, max: usize) -> Result<Option<Vec<u8>>, Failure> {
        let mut message: Option<Vec<u8>> = None;
        loop {
            let room = max - message.as_ref().map_or(0, Vec::len);
            let Frame {
                fin,
                opcode,
                payload,
            } = self.read_frame(room)?;
            match opcode {
                OP_PING => self.send(OP_PONG, &payload)?,
                OP_PONG => {}
                OP_CLOSE => return Ok(None),
                OP_TEXT if message.is_none() => message = Some(payload),
                OP_CONTINUATION => match message.as_mut() {
                    Some(m) => m.extend_from_slice(&payload),
                    None => return Err(Failure::Broken(1002, "a continuation of nothing")),
                },
                OP_TEXT => return Err(Failure::Broken(1002, "a message inside a message")),
                OP_BINARY if fin => {
                    return Err(Failure::Refused(1003, "only text messages are read", 0))
                }
                OP_BINARY => return Err(Failure::Broken(1003, "only text messages are read")),
                _ => return Err(Failure::Broken(1002, "an unknown opcode")),
            }
            if fin && opcode & 0x8 == 0 {
                if let Some(m) = message.take() {
                    if std::str::from_utf8(&m).is_err() {
                        return Err(Failure::Refused(1007, "a text message is UTF-8", 0));
                    }
                    return Ok(Some(m));
                }
            }
        }
    }

    /// Reads and drops `n` bytes.
    fn skip(&mut self, n: u64) -> io::Result<()> {
        let copied = io::copy(&mut (&mut self.stream).take(n), &mut io::sink())?;
        if copied < n {
            return Err(io::ErrorKind::UnexpectedEof.into());
        }
        Ok(())
    }

    /// After the server's close: the client's frames read and dropped until its close (or
    /// until it goes away), as RFC 6455 asks, so that it reads the server's close whole.
    fn linger(&mut self, max: usize) {
        while let Ok(frame) = self.read_frame(max) {
            if frame.opcode == OP_CLOSE {
                return;
            }
        }
    }

    /// Sends one whole frame, written at once.
    fn send(&mut self, opcode: u8, payload: &[u8]) -> io::Result<()> {
        let mut frame = Vec::with_capacity(payload.len() + 10);
        frame.push(0x80 | opcode);
        match payload.len() {
            n if n < 126 => frame.push(n as u8),
            n if n <= usize::from(u16::MAX) => {
                frame.push(126);
                frame.extend_from_slice(&(n as u16).to_be_bytes());
            }
            n => {
                frame.push(127);
                frame.extend_from_slice(&(n as u64).to_be_bytes());
            }
        }
        frame.extend_from_slice(payload);
        self.stream.write_all(&frame)?;
        self.stream.flush()
    }

    /// Closes the socket with `code`, saying `why`.
    fn close(&mut self, code: u16, why: &str) {
        let mut payload = code.to_be_bytes().to_vec();
        payload.extend_from_slice(&why.as_bytes()[..why.len().min(123)]);
        let _ = self.send(OP_CLOSE, &payload);
    }
}

/// SHA-1 (FIPS 180-4), which the handshake needs and nothing else: not for security.
fn sha1(data: &[u8]) -> [u8; 20] {
    let mut h: [u32; 5] = [
        0x6745_2301,
        0xEFCD_AB89,
        0x98BA_DCFE,
        0x1032_5476,
        0xC3D2_E1F0,
    ];
    let mut padded = data.to_vec();
    padded.push(0x80);
    while padded.len() % 64 != 56 {
        padded.push(0);
    }
    padded.extend_from_slice(&((data.len() as u64).wrapping_mul(8)).to_be_bytes());
    for block in padded.chunks_exact(64) {
        let mut w = [0u32; 80];
        for (k, word) in block.chunks_exact(4).enumerate() {
            w[k] = u32::from_be_bytes([word[0], word[1], word[2], word[3]]);
        }
        for k in 16..80 {
            w[k] = (w[k - 3] ^ w[k - 8] ^ w[k - 14] ^ w[k - 16]).rotate_left(1);
        }
        let [mut a, mut b, mut c, mut d, mut e] = h;
        for (k, wk) in w.iter().enumerate() {
            let (f, constant) = match k {
                0..=19 => ((b & c) | (!b & d), 0x5A82_7999),
                20..=39 => (b ^ c ^ d, 0x6ED9_EBA1),
                40..=59 => ((b & c) | (b & d) | (c & d), 0x8F1B_BCDC),
                _ => (b ^ c ^ d, 0xCA62_C1D6),
            };
            let t = (a.rotate_left(5))
                .wrapping_add(f)
                .wrapping_add(e)
                .wrapping_add(constant)
                .wrapping_add(*wk);
            (e, d, c, b, a) = (d, c, b.rotate_left(30), a, t);
        }
        for (hk, v) in h.iter_mut().zip([a, b, c, d, e]) {
            *hk = hk.wrapping_add(v);
        }
    }
    let mut out = [0u8; 20];
    for (chunk, v) in out.chunks_exact_mut(4).zip(h) {
        chunk.copy_from_slice(&v.to_be_bytes());
    }
    out
}

/// Base64 with padding (RFC 4648, section 4).
fn base64(bytes: &[u8]) -> String {
    const ALPHABET: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let n = (u32::from(chunk[0]) << 16)
            | (u32::from(chunk.get(1).copied().unwrap_or(0)) << 8)
            | u32::from(chunk.get(2).copied().unwrap_or(0));
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(char::from(ALPHABET[(n >> (18 - 6 * k) & 0x3F) as usize]));
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hex(bytes: &[u8]) -> String {
        bytes.iter().map(|b| format!("{b:02x}")).collect()
    }

    #[test]
    fn sha1_and_base64_give_the_known_values() {
        assert_eq!(hex(&sha1(b"")), "da39a3ee5e6b4b0d3255bfef95601890afd80709");
        assert_eq!(
            hex(&sha1(b"abc")),
            "a9993e364706816aba3e25717850c26c9cd0d89d"
        );
        let long = b"abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
        assert_eq!(hex(&sha1(long)), "84983e441c3bd26ebaae4aa1f95129e5e54670f1");
        let million = vec![b'a'; 1_000_000];
        assert_eq!(
            hex(&sha1(&million)),
            "34aa973cd4c4daa4f61eeb2bdbad27316534016f"
        );
        for (text, coded) in [
            ("", ""),
            ("f", "Zg=="),
            ("fo", "Zm8="),
            ("foo", "Zm9v"),
            ("foob", "Zm9vYg=="),
            ("fooba", "Zm9vYmE="),
            ("foobar", "Zm9vYmFy"),
        ] {
            assert_eq!(base64(text.as_bytes()), coded, "{text}");
        }
    }

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
