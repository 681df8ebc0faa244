// link.cpp: the frame format of ../PROTOCOL.md section "Frames".
#include "link.h"

uint8_t crc8(const char *data, uint8_t n) {  // poly 0x07, init 0, not reflected, xorout 0
  uint8_t crc = 0;
  for (uint8_t i = 0; i < n; i++) {
    crc ^= (uint8_t)data[i];
    for (uint8_t b = 0; b < 8; b++) crc = (crc & 0x80) ? (uint8_t)((crc << 1) ^ 0x07) : (crc << 1);
  }
  return crc;
}

static const char HEX_DIGITS[] = "0123456789ABCDEF";

Out &Out::begin(uint8_t seq) {
  len = 0;
  buf[0] = 0;
  return num(seq);
}

Out &Out::word(const char *w) {
  if (len > 0 && len < MAX_BODY) buf[len++] = ' ';
  while (*w && len < MAX_BODY) buf[len++] = *w++;
  buf[len] = 0;
  return *this;
}

Out &Out::num(long v) {
  char tmp[12];
  ltoa(v, tmp, 10);
  return word(tmp);
}

void Out::send() {
  uint8_t c = crc8(buf, len);
  Serial.write((const uint8_t *)buf, len);
  char tail[4] = {'*', HEX_DIGITS[c >> 4], HEX_DIGITS[c & 15], '\n'};
  Serial.write((const uint8_t *)tail, 4);
}

void Link::begin() { n_ = 0; overflow_ = false; }

LineResult Link::poll() {
  while (Serial.available() > 0) {
    char ch = (char)Serial.read();
    if (ch == '\n') {
      LineResult r = overflow_ ? LINE_MALFORMED : finish();
      n_ = 0;
      overflow_ = false;
      return r;
    }
    if (n_ < sizeof(line_)) line_[n_++] = ch;
    else overflow_ = true;  // longer than any frame: answered 0 ER 9 at its newline
  }
  return LINE_NONE;
}

static int8_t hexval(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;  // lowercase is not allowed on the wire
}

bool parse_long(const char *s, long *out) {
  bool neg = false;
  if (*s == '-') { neg = true; s++; }
  if (!*s) return false;
  long long v = 0;
  for (; *s; s++) {
    if (*s < '0' || *s > '9') return false;
    v = v * 10 + (*s - '0');
    if (v > 2147483648LL) return false;
  }
  if (neg) v = -v;
  if (v > 2147483647LL || v < -2147483648LL) return false;
  *out = (long)v;
  return true;
}

// -?[0-9]+: a token that reads as an integer (whether or not it fits int32)
static bool looks_like_int(const char *s) {
  if (*s == '-') s++;
  if (!*s) return false;
  for (; *s; s++)
    if (*s < '0' || *s > '9') return false;
  return true;
}

static bool is_word_char(char c) {
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
         c == '_' || c == '.' || c == ':' || c == '-';
}

LineResult Link::finish() {
  uint8_t n = n_;
  if (n > 0 && line_[n - 1] == '\r') n--;
  if (n < 4 || line_[n - 3] != '*') return LINE_MALFORMED;
  int8_t hi = hexval(line_[n - 2]), lo = hexval(line_[n - 1]);
  if (hi < 0 || lo < 0) return LINE_MALFORMED;
  uint8_t blen = n - 3;
  if (blen > MAX_BODY) return LINE_MALFORMED;
  if (crc8(line_, blen) != (uint8_t)((hi << 4) | lo)) return LINE_CHECKSUM;
  for (uint8_t i = 0; i < blen; i++)
    if (line_[i] < 0x20 || line_[i] > 0x7E || line_[i] == '*') return LINE_MALFORMED;
  memcpy(body, line_, blen);
  body[blen] = 0;
  memcpy(tok_buf, body, blen + 1);
  // tokens separated by exactly one space
  ntok = 0;
  char *p = tok_buf;
  while (true) {
    if (*p == 0 || *p == ' ') return LINE_MALFORMED;  // empty token
    if (ntok >= MAX_TOKENS) return LINE_MALFORMED;
    tokens[ntok++] = p;
    while (*p && *p != ' ') p++;
    if (*p == 0) break;
    *p++ = 0;
  }
  if (ntok < 2) return LINE_MALFORMED;
  long s;
  const char *t = tokens[0];
  for (const char *q = t; *q; q++) if (*q < '0' || *q > '9') return LINE_MALFORMED;
  if (t[0] == '0' && t[1]) return LINE_MALFORMED;  // no leading zeros
  if (!parse_long(t, &s) || s > 255) return LINE_MALFORMED;
  seq = (uint8_t)s;
  t = tokens[1];
  if (strlen(t) != 2 || t[0] < 'A' || t[0] > 'Z' || t[1] < 'A' || t[1] > 'Z')
    return LINE_MALFORMED;
  for (uint8_t i = 2; i < ntok; i++) {
    long v;
    if (parse_long(tokens[i], &v)) continue;
    // an integer outside int32 is malformed, not a word (as the host's decode_frame says)
    if (looks_like_int(tokens[i])) return LINE_MALFORMED;
    for (const char *q = tokens[i]; *q; q++) if (!is_word_char(*q)) return LINE_MALFORMED;
  }
  return LINE_OK;
}
