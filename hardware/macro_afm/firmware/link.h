// link.h: protocol version 1 framing (BODY*CC\n, CRC-8/SMBUS) on Serial (UART0).
#ifndef MACRO_AFM_LINK_H
#define MACRO_AFM_LINK_H
#include <Arduino.h>

#define MAX_BODY 120
#define MAX_TOKENS 8

uint8_t crc8(const char *data, uint8_t n);

// A frame being written: append tokens, then send() adds " " separators, *CC and \n.
class Out {
 public:
  Out &begin(uint8_t seq);
  Out &word(const char *w);
  Out &num(long v);
  void send();  // to Serial
  char buf[MAX_BODY + 1];
  uint8_t len = 0;
};

// A received line: Link::poll() returns one of these results when a line is complete.
enum LineResult { LINE_NONE = 0, LINE_OK, LINE_CHECKSUM, LINE_MALFORMED };

class Link {
 public:
  void begin();
  // Read what Serial holds; on a complete valid line, body holds BODY (NUL-terminated) and
  // tokens/ntok its tokens (pointers into tok_buf, a copy). seq is the parsed SEQ.
  LineResult poll();
  char body[MAX_BODY + 1];
  char tok_buf[MAX_BODY + 1];
  char *tokens[MAX_TOKENS];
  uint8_t ntok = 0;
  uint8_t seq = 0;

 private:
  LineResult finish();
  char line_[MAX_BODY + 5];  // BODY*CC (and a \r)
  uint8_t n_ = 0;
  bool overflow_ = false;
};

bool parse_long(const char *s, long *out);  // -?[0-9]+ fitting int32
#endif
