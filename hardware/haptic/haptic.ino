// haptic.ino: a one-axis haptic force-feedback device for the afmsmiler course (module (h)).
//
// A DC motor with a quadrature encoder drives a handle through a capstan (as in the Hapkit); a
// current-mode servo amplifier (maxon ESCON) turns a PWM set value into motor current, so the
// handle's force is the set value times the force constant KT. Every 1 ms the loop reads the
// encoder, computes the force (the host's streamed force, a virtual spring and wall, and the Q
// controller), clips it at MF and writes the set value; between ticks it serves the serial
// protocol (PROTOCOL.md): commands with replies, FO force frames (SEQ 0) from the host, and the
// PO position stream. Safety: no FO frame for WD ms while ACTIVE zeroes the current (event
// WATCHDOG, state IDLE); the E-stop button or ES, and leaving the travel XL, zero it and latch
// FAULT until DS. afmsmiler/hardware/haptic/twin.py runs the same loop in Python.
//
// Board: Arduino Uno R3 (ATmega328P, 16 MHz): 1 000 000 baud is exact (UBRR 1, U2X).
// Build: hardware/haptic/build.sh (avr-gcc and Debian's arduino-core-avr), or the Arduino IDE.
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <stdio.h>

#include "config.h"
#include "protocol.h"

// -- pins (WIRING.md) -------------------------------------------------------------------------
const uint8_t PIN_ENC_A = 2;   // INT0, encoder channel A
const uint8_t PIN_ENC_B = 3;   // INT1, encoder channel B
const uint8_t PIN_ESTOP = 7;   // E-stop: normally-closed button to GND, pull-up: HIGH = pressed
const uint8_t PIN_ENABLE = 8;  // ESCON digital input 2: enable
const uint8_t PIN_PWM = 9;     // OC1A -> ESCON digital input 1: PWM set value (10..90 %)
const uint8_t PIN_LED = 13;    // on while ACTIVE

// -- timing and electronics ---------------------------------------------------------------------
const unsigned long TICK_US = 1000UL;     // the control period
const float TICK_S = 1e-3f;
const float AMP_BANDWIDTH_HZ = 1000.0f;   // the ESCON current loop, first-order (twin: Mechanics)
const uint16_t PWM_TOP = 3999;            // Timer1 fast PWM at 16 MHz / 4000 = 4 kHz
const uint16_t PWM_LOW = 400;             // 10 % duty = -current limit
const uint16_t PWM_SPAN = 3200;           // 90 % duty = +current limit

// -- parameters: limits and defaults (afmsmiler/hardware/haptic/codec.py PARAMETERS) ----------
enum ParamIndex {
  P_MAX_FORCE, P_FORCE_SCALE, P_SPRING, P_WALL_STIFFNESS, P_WALL_POSITION, P_QGAIN, P_QPHASE,
  P_QFREQ, P_WATCHDOG, P_VFILTER, P_TRAVEL, P_RESOLUTION, P_FORCE_CONSTANT, P_CURRENT_LIMIT,
  P_COUNT
};

struct Limits {
  long low, high, def;
  bool read_only;
};

const Limits LIMITS[P_COUNT] = {
  /* [P_MAX_FORCE] = */ {0L, 5000000L, 2000000L, false},
  /* [P_FORCE_SCALE] = */ {-1000000L, 1000000L, 1000L, false},
  /* [P_SPRING] = */ {0L, 2000000L, 0L, false},
  /* [P_WALL_STIFFNESS] = */ {0L, 5000000L, 0L, false},
  /* [P_WALL_POSITION] = */ {-50000L, 50000L, 10000L, false},
  /* [P_QGAIN] = */ {-10000L, 10000L, 0L, false},
  /* [P_QPHASE] = */ {-180000L, 180000L, 90000L, false},
  /* [P_QFREQ] = */ {100L, 1000000L, 10000L, false},
  /* [P_WATCHDOG] = */ {5L, 1000L, 50L, false},
  /* [P_VFILTER] = */ {10L, 500L, 200L, false},
  /* [P_TRAVEL] = */ {1000L, 60000L, 40000L, false},
  /* [P_RESOLUTION] = */ {1L, 100000L, 7670L, true},
  /* [P_FORCE_CONSTANT] = */ {1L, 1000000L, 1760L, true},
  /* [P_CURRENT_LIMIT] = */ {1L, 100000L, 1500L, true},
};

const char *const PAR_CODES[P_COUNT] = {
  PAR_MAX_FORCE, PAR_FORCE_SCALE, PAR_SPRING, PAR_WALL_STIFFNESS, PAR_WALL_POSITION, PAR_QGAIN,
  PAR_QPHASE, PAR_QFREQ, PAR_WATCHDOG, PAR_VFILTER, PAR_TRAVEL, PAR_RESOLUTION,
  PAR_FORCE_CONSTANT, PAR_CURRENT_LIMIT
};

long params[P_COUNT];

// -- state --------------------------------------------------------------------------------------
enum State { IDLE, ACTIVE, FAULT };
const char *const STATE_WORDS[] = {"IDLE", "ACTIVE", "FAULT"};
State state = IDLE;
uint8_t flags = 0;
uint8_t fault_code = ERR_STATE;

volatile long enc_count = 0;
volatile uint8_t enc_state = 0;
long zero_offset = 0;
long prev_count = 0;
float xf = 0.0f, vf = 0.0f;        // filtered position (m) and velocity (m/s)
float alpha = 0.0f;                // low-pass coefficient
float q_cos = 0.0f, q_sin = 0.0f;  // compensated Q-control coefficients (1, s)
float stream_force = 0.0f;         // the host's last FO force, N
float command_force = 0.0f;        // the force last asked of the motor, N
unsigned long ticks = 0;           // ms since boot
unsigned long last_force_tick = 0;
unsigned long next_tick_us = 0;
uint16_t stream_ms = 0;            // 0: no PO stream
unsigned long next_stream_tick = 0;

// -- the encoder (both channels on interrupts: x4 decoding) -----------------------------------
// Index (old state << 2) | new state, state = A + 2 B; +-2 marks a jump over one state (two
// edges before the interrupt ran): counted twice in the direction of the last single step.
const int8_t QUADRATURE[16] = {0, -1, 1, 2, 1, 0, 2, -1, -1, 2, 0, 1, 2, 1, -1, 0};
volatile int8_t enc_dir = 1;

void encoder_isr() {
  uint8_t now = (PIND >> 2) & 3;  // pins 2, 3 = PD2 (A), PD3 (B)
  int8_t step = QUADRATURE[(enc_state << 2) | now];
  if (step == 2) {
    enc_count += 2 * enc_dir;
  } else if (step) {
    enc_count += step;
    enc_dir = step;
  }
  enc_state = now;
}

long read_count() {
  noInterrupts();
  long c = enc_count;
  interrupts();
  return c;
}

// -- the motor ------------------------------------------------------------------------------------
void write_current(float amps) {
  float limit = params[P_CURRENT_LIMIT] * 1e-3f;
  if (amps > limit) amps = limit;
  if (amps < -limit) amps = -limit;
  OCR1A = (uint16_t)(PWM_LOW + (amps / limit + 1.0f) * 0.5f * PWM_SPAN + 0.5f);
}

void motor_off() {
  write_current(0.0f);
  digitalWrite(PIN_ENABLE, LOW);
  digitalWrite(PIN_LED, LOW);
}

// -- frames -----------------------------------------------------------------------------------
uint8_t crc8(const char *s, uint8_t n) {
  uint8_t crc = 0;
  for (uint8_t i = 0; i < n; i++) {
    crc ^= (uint8_t)s[i];
    for (uint8_t b = 0; b < 8; b++)
      crc = (crc & 0x80) ? (uint8_t)((crc << 1) ^ 0x07) : (uint8_t)(crc << 1);
  }
  return crc;
}

char last_body[124];   // the last command executed (retries get its reply again)
char last_reply[128];

void send_body(const char *body) {
  static const char HEX_DIGITS[] = "0123456789ABCDEF";
  uint8_t c = crc8(body, (uint8_t)strlen(body));
  Serial.print(body);
  Serial.write('*');
  Serial.write(HEX_DIGITS[c >> 4]);
  Serial.write(HEX_DIGITS[c & 15]);
  Serial.write('\n');
}

void send_event(const char *word) {
  char body[32];
  snprintf(body, sizeof body, "0 EV %s", word);
  send_body(body);
}

void send_error0(uint8_t err) {
  char body[16];
  snprintf(body, sizeof body, "0 ER %u", err);
  send_body(body);
}

// a reply to command `seq`: remembered for retries
void reply(uint8_t seq, const char *fmt_rest) {
  snprintf(last_reply, sizeof last_reply, "%u %s", seq, fmt_rest);
  send_body(last_reply);
}

// -- the Q controller's compensation (the twin's HapticTwin._compensate) -------------------------
void compensate() {
  float f_ref = params[P_QFREQ] * 1e-3f;
  float w = 2.0f * (float)M_PI * f_ref;
  alpha = 1.0f - expf(-2.0f * (float)M_PI * params[P_VFILTER] * TICK_S);
  float zr = cosf(w * TICK_S), zi = -sinf(w * TICK_S);            // z = e^{-i w T}
  float nr = alpha * zr, ni = alpha * zi;                          // alpha z
  float dr = 1.0f - (1.0f - alpha) * zr, di = -(1.0f - alpha) * zi;  // 1 - (1 - alpha) z
  float den = dr * dr + di * di;
  float hr = (nr * dr + ni * di) / den, hi = (ni * dr - nr * di) / den;
  float ar = 1.0f, ai = f_ref / AMP_BANDWIDTH_HZ;                  // / (1 + i f / f_amp)
  float aden = ar * ar + ai * ai;
  float gr = (hr * ar + hi * ai) / aden, gi = (hi * ar - hr * ai) / aden;
  float mag = sqrtf(gr * gr + gi * gi);
  float gain = params[P_QGAIN] * 1e-3f / mag;
  float phase = params[P_QPHASE] * ((float)M_PI / 180e3f) + atan2f(gi, gr);
  q_cos = gain * cosf(phase);
  q_sin = gain * sinf(phase) / w;
}

// -- faults -----------------------------------------------------------------------------------
void fault(const char *event, uint8_t flag, uint8_t code) {
  state = FAULT;
  flags |= flag;
  fault_code = code;
  stream_force = 0.0f;
  command_force = 0.0f;
  motor_off();
  send_event(event);
}

// -- one control tick (1 ms) ---------------------------------------------------------------------
void tick() {
  long count = read_count() - zero_offset;
  float res = params[P_RESOLUTION] * 1e-9f;
  float x = count * res, x_prev = prev_count * res;
  xf += alpha * (0.5f * (x + x_prev) - xf);
  vf += alpha * ((x - x_prev) / TICK_S - vf);
  prev_count = count;
  float force = 0.0f;
  if (state != FAULT && digitalRead(PIN_ESTOP) == HIGH) {  // pressed (or its wire broken)
    fault(EVT_ESTOP, FLAG_ESTOP, ERR_ESTOP);
  }
  if (state == ACTIVE) {
    if (ticks - last_force_tick > (unsigned long)params[P_WATCHDOG]) {
      state = IDLE;
      flags |= FLAG_WATCHDOG;
      stream_force = 0.0f;
      motor_off();
      send_event(EVT_WATCHDOG);
    } else if (fabsf(x) > params[P_TRAVEL] * 1e-6f) {
      fault(EVT_LIMIT, FLAG_LIMIT, ERR_LIMIT);
    } else {
      float ks = params[P_SPRING] * 1e-3f;
      force = stream_force * params[P_FORCE_SCALE] * 1e-3f - ks * x;
      float xw = params[P_WALL_POSITION] * 1e-6f;
      if (x > xw) force -= params[P_WALL_STIFFNESS] * 1e-3f * (x - xw);
      force += ks * (q_cos * xf - q_sin * vf);
      float limit = params[P_MAX_FORCE] * 1e-6f;
      if (fabsf(force) > limit) {
        force = force > 0 ? limit : -limit;
        flags |= FLAG_SATURATED;
      }
      write_current(force / (params[P_FORCE_CONSTANT] * 1e-3f));
    }
  }
  command_force = force;
  ticks++;
  if (stream_ms && ticks >= next_stream_tick) {
    char body[48];
    snprintf(body, sizeof body, "0 PO %ld %ld %lu", lroundf(x * 1e6f), lroundf(vf * 1e6f),
             (unsigned long)(micros() & 0x7FFFFFFFUL));
    send_body(body);
    next_stream_tick += stream_ms;
  }
}

// -- commands -------------------------------------------------------------------------------------
int find_param(const char *code) {
  for (int i = 0; i < P_COUNT; i++)
    if (strcmp(code, PAR_CODES[i]) == 0) return i;
  return -1;
}

// token checks: an int32 "-?[0-9]+" or a word "[A-Za-z0-9_.:-]+"
bool is_int(const char *t) {
  const char *p = (*t == '-') ? t + 1 : t;
  if (!*p || strlen(p) > 10) return false;
  for (; *p; p++)
    if (*p < '0' || *p > '9') return false;
  return true;
}

bool is_word(const char *t) {
  if (!*t) return false;
  for (; *t; t++) {
    char c = *t;
    if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
          c == '_' || c == '.' || c == ':' || c == '-'))
      return false;
  }
  return true;
}

void execute(uint8_t seq, const char *code, char **args, uint8_t n) {
  char out[96];
  if (strcmp(code, CMD_FORCE) == 0) {  // the stream: no reply
    if (seq == 0 && n == 1 && is_int(args[0])) {
      stream_force = atol(args[0]) * 1e-6f;
      last_force_tick = ticks;
    } else if (seq != 0) {
      snprintf(out, sizeof out, "ER %d", ERR_BAD_ARGUMENT);
      reply(seq, out);
    }
    return;
  }
  if (seq == 0) return;  // other SEQ 0 frames from the host are not ours
  if (strcmp(code, CMD_IDENTIFY) == 0) {
    snprintf(out, sizeof out, "OK ID %s %d %s", DEVICE_NAME, PROTOCOL_VERSION, FIRMWARE_VERSION);
  } else if (strcmp(code, CMD_SET) == 0) {
    int p = (n == 2) ? find_param(args[0]) : -1;
    long v = (p >= 0 && is_int(args[1])) ? atol(args[1]) : 0;
    if (p < 0 || !is_int(args[1])) {
      snprintf(out, sizeof out, "ER %d", ERR_BAD_ARGUMENT);
    } else if (LIMITS[p].read_only || v < LIMITS[p].low || v > LIMITS[p].high) {
      snprintf(out, sizeof out, "ER %d %s", ERR_BAD_ARGUMENT, PAR_CODES[p]);
    } else {
      params[p] = v;
      compensate();
      snprintf(out, sizeof out, "OK SP %s %ld", PAR_CODES[p], v);
    }
  } else if (strcmp(code, CMD_GET) == 0) {
    int p = (n == 1) ? find_param(args[0]) : -1;
    if (p < 0) snprintf(out, sizeof out, "ER %d", ERR_BAD_ARGUMENT);
    else snprintf(out, sizeof out, "OK GP %s %ld", PAR_CODES[p], params[p]);
  } else if (strcmp(code, CMD_ENABLE) == 0) {
    if (state == FAULT) {
      snprintf(out, sizeof out, "ER %d", fault_code);
    } else {
      state = ACTIVE;
      last_force_tick = ticks;
      digitalWrite(PIN_ENABLE, HIGH);
      digitalWrite(PIN_LED, HIGH);
      snprintf(out, sizeof out, "OK EN");
    }
  } else if (strcmp(code, CMD_DISABLE) == 0) {
    state = IDLE;
    stream_force = 0.0f;
    command_force = 0.0f;
    motor_off();
    snprintf(out, sizeof out, "OK DS");
  } else if (strcmp(code, CMD_ZERO) == 0) {
    if (state == ACTIVE) {
      snprintf(out, sizeof out, "ER %d", ERR_STATE);
    } else {
      zero_offset = read_count();
      prev_count = 0;
      xf = vf = 0.0f;
      snprintf(out, sizeof out, "OK ZR");
    }
  } else if (strcmp(code, CMD_STREAM) == 0) {
    long ms = (n == 1 && is_int(args[0])) ? atol(args[0]) : -1;
    if (ms < 0 || ms > 1000) {
      snprintf(out, sizeof out, "ER %d", ERR_BAD_ARGUMENT);
    } else {
      stream_ms = (uint16_t)ms;
      next_stream_tick = ticks + ms;
      snprintf(out, sizeof out, "OK SS %ld", ms);
    }
  } else if (strcmp(code, CMD_STATUS) == 0) {
    float res = params[P_RESOLUTION] * 1e-9f;
    long um = lroundf((read_count() - zero_offset) * res * 1e6f);
    snprintf(out, sizeof out, "OK ST %s %u %ld %ld", STATE_WORDS[state], flags, um,
             lroundf(command_force * 1e6f));
    flags = 0;
  } else if (strcmp(code, CMD_ESTOP) == 0) {
    fault(EVT_ESTOP, FLAG_ESTOP, ERR_ESTOP);
    snprintf(out, sizeof out, "OK ES");
  } else {
    snprintf(out, sizeof out, "ER %d %s", ERR_UNKNOWN_COMMAND, code);
  }
  reply(seq, out);
}

// one received line: check the frame, answer a damaged one with 0 ER 1 / 0 ER 9, run the rest
void handle_line(char *line, uint8_t len) {
  char *star = strrchr(line, '*');
  if (!star || line + len - star != 3 || star - line > 120 || star == line) {
    send_error0(ERR_MALFORMED);
    return;
  }
  *star = 0;
  uint8_t body_len = (uint8_t)(star - line);
  for (uint8_t i = 0; i < body_len; i++) {
    if (line[i] < 0x20 || line[i] > 0x7E) {
      send_error0(ERR_MALFORMED);
      return;
    }
  }
  char *hex = star + 1;
  char *end;
  uint8_t given = (uint8_t)strtoul(hex, &end, 16);
  bool upper = (hex[0] < 'a' || hex[0] > 'f') && (hex[1] < 'a' || hex[1] > 'f');
  if (end != hex + 2 || !upper) {
    send_error0(ERR_MALFORMED);
    return;
  }
  if (given != crc8(line, body_len)) {
    send_error0(ERR_CHECKSUM);
    return;
  }
  // a retry of the last command: the same reply, not executed again
  bool retry = strcmp(line, last_body) == 0 && line[0] != '0';
  char copy[124];
  strcpy(copy, line);
  char *tokens[12];
  uint8_t n = 0;
  char *save = line;
  for (char *p = line;; p++) {
    if (*p == ' ' || *p == 0) {
      bool last = (*p == 0);
      *p = 0;
      if (n == 12 || p == save) {
        send_error0(ERR_MALFORMED);
        return;
      }
      tokens[n++] = save;
      save = p + 1;
      if (last) break;
    }
  }
  if (n < 2 || !is_int(tokens[0]) || strlen(tokens[1]) != 2 || tokens[1][0] < 'A' ||
      tokens[1][0] > 'Z' || tokens[1][1] < 'A' || tokens[1][1] > 'Z') {
    send_error0(ERR_MALFORMED);
    return;
  }
  long seq = atol(tokens[0]);
  if (seq < 0 || seq > 255) {
    send_error0(ERR_MALFORMED);
    return;
  }
  for (uint8_t i = 2; i < n; i++) {
    if (!is_int(tokens[i]) && !is_word(tokens[i])) {
      send_error0(ERR_MALFORMED);
      return;
    }
  }
  if (retry) {
    send_body(last_reply);
    return;
  }
  if (seq != 0) strcpy(last_body, copy);
  execute((uint8_t)seq, tokens[1], tokens + 2, (uint8_t)(n - 2));
}

// -- serial input: a line buffer filled between ticks -------------------------------------------
char rx[132];
uint8_t rx_len = 0;

void serve_serial() {
  while (Serial.available() > 0) {
    char c = (char)Serial.read();
    if (c == '\n') {
      if (rx_len && rx[rx_len - 1] == '\r') rx_len--;
      rx[rx_len] = 0;
      handle_line(rx, rx_len);
      rx_len = 0;
    } else if (rx_len < sizeof rx - 1) {
      rx[rx_len++] = c;
    } else {  // an over-long line: junk, answered once it ends
      rx_len = sizeof rx - 1;
    }
  }
}

void setup() {
  for (int i = 0; i < P_COUNT; i++) params[i] = LIMITS[i].def;
  pinMode(PIN_ENC_A, INPUT_PULLUP);
  pinMode(PIN_ENC_B, INPUT_PULLUP);
  pinMode(PIN_ESTOP, INPUT_PULLUP);
  pinMode(PIN_ENABLE, OUTPUT);
  pinMode(PIN_LED, OUTPUT);
  pinMode(PIN_PWM, OUTPUT);
  // Timer1: fast PWM, TOP = ICR1 (mode 14), no prescaler, non-inverting on OC1A
  TCCR1A = _BV(COM1A1) | _BV(WGM11);
  TCCR1B = _BV(WGM13) | _BV(WGM12) | _BV(CS10);
  ICR1 = PWM_TOP;
  motor_off();
  enc_state = (PIND >> 2) & 3;
  attachInterrupt(digitalPinToInterrupt(PIN_ENC_A), encoder_isr, CHANGE);
  attachInterrupt(digitalPinToInterrupt(PIN_ENC_B), encoder_isr, CHANGE);
  compensate();
  last_body[0] = 0;
  Serial.begin(BAUD_RATE);
  send_event(EVT_BOOT);
  next_tick_us = micros() + TICK_US;
}

void loop() {
  serve_serial();
  if ((long)(micros() - next_tick_us) >= 0) {
    next_tick_us += TICK_US;
    tick();
  }
}
