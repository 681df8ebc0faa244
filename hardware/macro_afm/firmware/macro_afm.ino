// macro_afm.ino: firmware of the macroscopic AFM (module (h) of afmsmiler), Arduino Mega 2560.
//
// A steel ruler with a foil strain gauge at its clamp (read by an HX711) carries a needle over a
// 3D-printed sample; three Ender 3 stepper axes move it. Contact mode regulates the deflection at
// each pixel by stepping z; jumping mode approaches to the deflection setpoint, records, lifts by
// LIFT and moves while lifted. The serial protocol is ../PROTOCOL.md (protocol.h has its numbers);
// pins and mechanics are in config.h (../WIRING.md). Everything runs from loop() without blocking,
// except the emergency stop, which is an interrupt that disables the drivers at once.
#include <avr/sleep.h>

#include "config.h"
#include "protocol.h"
#include "axis.h"
#include "hx711.h"
#include "link.h"

enum State { S_IDLE, S_HOMING, S_SCANNING, S_PAUSED, S_FAULT };
static const char *const STATE_WORDS[] = {"IDLE", "HOMING", "SCANNING", "PAUSED", "FAULT"};

// Scan phases (inside S_SCANNING)
enum Phase {
  P_WAIT_MOVE,  // wait until every axis stopped, then go to `after_move`
  P_ORIGIN,     // travel (lifted) to pixel (0, 0)
  P_FREE,       // average FREE_SAMPLES readings out of contact
  P_DESCEND,    // start an approach
  P_APPROACH,   // descend until the gauge shows contact
  P_CAL1,       // first contact: reading before pressing in by CAL_STEPS
  P_CAL2,       // reading after pressing in: counts per z micro-step
  P_REGULATE,   // step z until the deflection is the setpoint, then record the pixel
  P_NEXT,       // choose the next pixel; lift if the mode (or a new line) says so
  P_TRAVEL,     // move x and y to the pixel
  P_FINISH      // lifted after the last line: DONE
};

// -- parameters ---------------------------------------------------------------------------------
struct Params {
  long nx = 8, ny = 8, pitch = 200, setpoint = 2000, mode = 0, lift = 400;
  long speed = 4000, accel = 40000, preset = 0;
};
static Params par;

struct Preset { int16_t nx, ny, pitch, mode, lift; };
// 0: the current parameters; 1: a quick 16 x 16 test; 2, 3: the paper's 128 x 128 at 0.2 mm in
// contact and jumping mode (lift 1 mm).
static const Preset PRESETS[N_PRESETS] = {
    {0, 0, 0, 0, 0}, {16, 16, 500, 0, 400}, {128, 128, 200, 0, 400}, {128, 128, 200, 1, 400}};

// -- hardware ------------------------------------------------------------------------------------
static Axis axes[3];  // x, y, z
static const char AXIS_NAMES[3][2] = {"X", "Y", "Z"};
static HX711 gauge;
static Link link;
static Out out;

// -- state --------------------------------------------------------------------------------------
static State state = S_IDLE;
static volatile bool estop_flag = false;
static bool homed = false;
static bool pause_requested = false;
static bool start_after_home = false;
static bool aborted = false;
static unsigned long scan_ms = 0;  // millis() at SS

// homing
static uint8_t home_axis = 0;  // 0: z, 1: x and y
static uint8_t home_stage[3];  // 0 start, 1 seek, 2 release, 3 back off, 4 done

// scan
static Phase phase = P_FREE, after_move = P_FREE;
static long row = 0, col = 0;
static long steps_per_pixel = 16;
static long free_level = 0, free_sum = 0;  // the free (tared) reading
static uint8_t tare_n = 0;                  // readings still to average for a tare (0: none)
static long tare_sum = 0;
static unsigned long tare_count = 0;
static uint8_t free_n = 0;
static unsigned long need_count = 0;  // gauge readings before this one are stale
static unsigned long settle_until = 0;
static int8_t gauge_sign = 1;          // sign of (reading - free) when the tip is pushed up
static float counts_per_step = 0;      // > 0 once calibrated
static long cal_d1 = 0;
static uint8_t reg_iter = 0;
static bool lifted = true;

// the current and the previous line, for GETLINE
struct Pixel { long z; long g; };  // z micro-steps, gauge counts above the free reading
static Pixel lines[2][MAX_NX];
static long line_row[2] = {-1, -1};
static uint8_t line_len[2] = {0, 0};

// retries: the last executed command's BODY and its reply
static int16_t last_seq = -1;
static char last_body[MAX_BODY + 1];
static char last_reply[MAX_BODY + 1];
static uint8_t last_reply_len = 0;

// display
static unsigned long display_ms = 0;
static long last_z = 0;

// -- helpers ------------------------------------------------------------------------------------
static bool switch_on(uint8_t pin) { return digitalRead(pin) == LOW; }
static bool estop_input() { return digitalRead(PIN_ESTOP) == HIGH; }  // NC switch opened

static void send_event(const char *w, const char *arg = nullptr) {
  out.begin(0).word("EV").word(w);
  if (arg) out.word(arg);
  out.send();
}

static void send_event_num(const char *w, long arg) {
  out.begin(0).word("EV").word(w).num(arg);
  out.send();
}

static void send_stream_error(int code) {
  out.begin(0).word("ER").num(code);
  out.send();
}

static void stop_all() {
  for (uint8_t i = 0; i < 3; i++) axes[i].hardStop();
}

static bool all_stopped() {
  return !axes[0].moving() && !axes[1].moving() && !axes[2].moving();
}

static void apply_profile(long speed) {
  for (uint8_t i = 0; i < 3; i++) axes[i].setProfile(speed, par.accel);
}

static void onEstop() {  // drivers off at once, the loop does the rest
  digitalWrite(PIN_ENABLE, HIGH);
  estop_flag = true;
}

// The E-stop's pin-change interrupt (PCINT4 on PB4 = pin 10; any change of port B's enabled pins).
ISR(PCINT0_vect) {
  if (estop_input()) onEstop();
}

static void fault(int code, const char *event, const char *arg) {
  stop_all();
  bool was_active = state == S_SCANNING || state == S_PAUSED || state == S_HOMING;
  if (event) send_event(event, arg);
  if (was_active) send_stream_error(code);
  state = S_FAULT;
  homed = false;
  start_after_home = false;
  pause_requested = false;
}

// Tare: the free reading becomes the average of the next FREE_SAMPLES readings (at boot and at the
// end of homing, with the needle up; a scan measures its own at pixel (0, 0) before approaching).
static void start_tare() {
  tare_n = FREE_SAMPLES;
  tare_sum = 0;
  tare_count = gauge.count;
}

static void tare_step() {
  if (tare_n == 0 || gauge.count == tare_count) return;
  tare_count = gauge.count;
  tare_sum += gauge.value;
  if (--tare_n == 0) free_level = tare_sum / FREE_SAMPLES;
}

// Gauge counts above the free reading, positive when the needle is pushed up.
static long deflection() { return gauge_sign * (gauge.value - free_level); }

static void sensor_fault() { fault(ERR_SENSOR, nullptr, nullptr); }

// -- lines ----------------------------------------------------------------------------------
static int8_t line_slot(long r) {
  for (int8_t i = 0; i < 2; i++)
    if (line_row[i] == r) return i;
  return -1;
}

static void send_pixel(long r, long c, const Pixel &p) {
  out.begin(0).word("PX").num(r).num(c).num(p.z).num(p.g);
  out.send();
}

static void record_pixel() {
  int8_t s = line_slot(row);
  if (s < 0) {  // a new line replaces the older of the two
    s = (line_row[0] < line_row[1]) ? 0 : 1;
    line_row[s] = row;
    line_len[s] = 0;
  }
  Pixel p = {axes[2].position, deflection()};
  lines[s][col] = p;
  line_len[s] = col + 1;
  last_z = p.z;
  send_pixel(row, col, p);
}

// -- motion phases -------------------------------------------------------------------------------
static void wait_move(Phase then) {
  phase = P_WAIT_MOVE;
  after_move = then;
}

static bool fresh_reading() {  // a reading converted entirely after the last stop
  return gauge.count >= need_count && (long)(millis() - settle_until) >= 0;
}


static void begin_approach() {
  apply_profile(par.speed);
  axes[2].moveTo(-Z_TRAVEL_STEPS);
  need_count = gauge.count + 1;
  phase = P_APPROACH;
}

static void start_scan() {
  steps_per_pixel = par.pitch * 1000L / XY_STEP_NM;
  row = 0;
  col = 0;
  line_row[0] = line_row[1] = -1;
  line_len[0] = line_len[1] = 0;
  counts_per_step = 0;
  pause_requested = false;
  lifted = true;
  scan_ms = millis();
  state = S_SCANNING;
  apply_profile(par.speed);
  axes[2].moveTo(0);  // tip up (home height) before travelling to the origin
  wait_move(P_ORIGIN);
}

static void lift() {
  long z = axes[2].position + par.lift;
  axes[2].moveTo(z > 0 ? 0 : z);
  lifted = true;
}

static void scan_step() {
  switch (phase) {
    case P_WAIT_MOVE:
      if (!all_stopped()) return;
      need_count = gauge.count + 2;  // skip the conversion that overlapped the motion
      settle_until = millis() + SETTLE_MS;
      phase = after_move;
      return;
    case P_ORIGIN:
      axes[0].moveTo(0);
      axes[1].moveTo(0);
      free_n = 0;
      free_sum = 0;
      wait_move(P_FREE);
      return;
    case P_FREE:
      if (!fresh_reading()) return;
      free_sum += gauge.value;
      need_count = gauge.count + 1;
      if (++free_n < FREE_SAMPLES) return;
      free_level = free_sum / FREE_SAMPLES;
      tare_n = 0;
      phase = P_DESCEND;
      return;
    case P_DESCEND:
      begin_approach();
      return;
    case P_APPROACH: {
      if (!axes[2].moving()) {  // the whole z travel without contact
        fault(ERR_LIMIT, EVT_LIMIT, "Z");
        return;
      }
      if (gauge.count < need_count) {
        if (millis() - gauge.last_ms > APPROACH_SENSOR_MS) sensor_fault();  // never descend blind
        return;
      }
      need_count = gauge.count + 1;
      long d = gauge.value - free_level;
      if (d > CONTACT_COUNTS || d < -CONTACT_COUNTS) {
        axes[2].hardStop();
        lifted = false;
        if (counts_per_step <= 0) gauge_sign = d > 0 ? 1 : -1;
        reg_iter = 0;
        wait_move(counts_per_step > 0 ? P_REGULATE : P_CAL1);
      }
      return;
    }
    case P_CAL1:
      if (!fresh_reading()) return;
      cal_d1 = deflection();
      axes[2].move(-CAL_STEPS);
      wait_move(P_CAL2);
      return;
    case P_CAL2: {
      if (!fresh_reading()) return;
      counts_per_step = (float)(deflection() - cal_d1) / (float)CAL_STEPS;
      if (counts_per_step < 0.5f) {  // the gauge does not follow z: broken or unglued
        counts_per_step = 0;
        sensor_fault();
        return;
      }
      reg_iter = 0;
      phase = P_REGULATE;  // this reading is fresh already
      return;
    }
    case P_REGULATE: {
      if (!fresh_reading()) return;
      long d = deflection();
      if (d < CONTACT_COUNTS) {  // lost contact (the surface fell away): approach again
        begin_approach();
        return;
      }
      float e = (float)(d - par.setpoint) / counts_per_step;
      long n = (long)(e >= 0 ? e + 0.5f : e - 0.5f);
      if (n != 0 && reg_iter < MAX_REG_ITER) {
        reg_iter++;
        axes[2].move(n);  // too much deflection (n > 0): raise z
        wait_move(P_REGULATE);
        return;
      }
      record_pixel();
      phase = P_NEXT;
      return;
    }
    case P_NEXT: {
      if (pause_requested) {
        pause_requested = false;
        state = S_PAUSED;
        send_event(EVT_PAUSED);
        return;
      }
      reg_iter = 0;
      if (col + 1 < par.nx) {
        col++;
        if (par.mode == 1) lift();  // jumping: lift, then move while lifted
      } else {
        out.begin(0).word("LN").num(row).num(col + 1);
        out.send();
        lift();  // every line starts lifted (no dragging back across the sample)
        if (row + 1 >= par.ny) {
          phase = P_FINISH;
          return;
        }
        row++;
        col = 0;
      }
      wait_move(P_TRAVEL);
      return;
    }
    case P_TRAVEL:
      axes[0].moveTo(col * steps_per_pixel);
      axes[1].moveTo(row * steps_per_pixel);
      wait_move(lifted ? P_DESCEND : P_REGULATE);
      return;
    case P_FINISH:
      if (!all_stopped()) return;
      state = S_IDLE;
      send_event(EVT_DONE);
      return;
  }
}

// -- homing: z up to Z_MAX first (tip away from the sample), then x and y to their MIN switches
static const uint8_t HOME_PIN[3] = {PIN_X_MIN, PIN_Y_MIN, PIN_Z_MAX};
static const int8_t HOME_DIR[3] = {-1, -1, +1};
static const long HOME_TRAVEL[3] = {X_TRAVEL_STEPS, Y_TRAVEL_STEPS, Z_TRAVEL_STEPS};

static void start_home() {
  stop_all();
  digitalWrite(PIN_ENABLE, LOW);
  homed = false;
  state = S_HOMING;
  home_axis = 0;
  home_stage[0] = home_stage[1] = 4;
  home_stage[2] = 0;
  for (uint8_t i = 0; i < 3; i++) axes[i].setProfile(HOME_SPEED, par.accel);
}

static bool home_one(uint8_t i) {  // true when axis i is homed
  Axis &a = axes[i];
  bool on = switch_on(HOME_PIN[i]);
  switch (home_stage[i]) {
    case 0:  // seek the switch, at most a whole travel and a tenth
      a.position = 0;
      a.moveTo(HOME_DIR[i] * (HOME_TRAVEL[i] + HOME_TRAVEL[i] / 10));
      home_stage[i] = 1;
      return false;
    case 1:
      if (on) {
        a.hardStop();
        a.position = 0;
        a.moveTo(-HOME_DIR[i] * HOME_BACKOFF * 4);
        home_stage[i] = 2;
      } else if (!a.moving()) {  // no switch over the whole travel: broken or unplugged
        fault(ERR_LIMIT, EVT_LIMIT, AXIS_NAMES[i]);
      }
      return false;
    case 2:  // move off until it opens, then HOME_BACKOFF more
      if (!on) {
        a.hardStop();
        a.position = 0;
        a.moveTo(-HOME_DIR[i] * HOME_BACKOFF);
        home_stage[i] = 3;
      } else if (!a.moving()) {
        fault(ERR_LIMIT, EVT_LIMIT, AXIS_NAMES[i]);
      }
      return false;
    case 3:
      if (a.moving()) return false;
      a.position = 0;
      home_stage[i] = 4;
      return true;
    default:
      return true;
  }
}

static void home_step() {
  if (home_axis == 0) {
    if (!home_one(2)) return;
    if (state != S_HOMING) return;
    home_axis = 1;
    home_stage[0] = home_stage[1] = 0;
    return;
  }
  bool x = home_one(0);
  if (state != S_HOMING) return;
  bool y = home_one(1);
  if (state != S_HOMING || !x || !y) return;
  homed = true;
  state = S_IDLE;
  start_tare();
  send_event(EVT_HOMED);
  if (start_after_home) {
    start_after_home = false;
    start_scan();
  }
}

// -- limit switches: any switch met while moving towards it stops everything ----------------------
static void check_limits() {
  static const uint8_t MIN_PIN[3] = {PIN_X_MIN, PIN_Y_MIN, PIN_Z_MIN};
  static const uint8_t MAX_PIN[3] = {PIN_X_MAX, PIN_Y_MAX, PIN_Z_MAX};
  for (uint8_t i = 0; i < 3; i++) {
    const Axis &a = axes[i];
    if (!a.moving()) continue;
    uint8_t pin = a.direction() < 0 ? MIN_PIN[i] : MAX_PIN[i];
    if (!switch_on(pin)) continue;
    if (state == S_HOMING && pin == HOME_PIN[i]) continue;  // homing looks for it
    fault(ERR_LIMIT, EVT_LIMIT, AXIS_NAMES[i]);
    return;
  }
}

// -- commands -------------------------------------------------------------------------------------
static bool param_index(const char *name, long **slot, bool *read_only) {
  *read_only = false;
  if (!strcmp(name, PAR_NX)) *slot = &par.nx;
  else if (!strcmp(name, PAR_NY)) *slot = &par.ny;
  else if (!strcmp(name, PAR_PITCH)) *slot = &par.pitch;
  else if (!strcmp(name, PAR_SETPOINT)) *slot = &par.setpoint;
  else if (!strcmp(name, PAR_MODE)) *slot = &par.mode;
  else if (!strcmp(name, PAR_LIFT)) *slot = &par.lift;
  else if (!strcmp(name, PAR_SPEED)) *slot = &par.speed;
  else if (!strcmp(name, PAR_ACCEL)) *slot = &par.accel;
  else if (!strcmp(name, PAR_PRESET)) *slot = &par.preset;
  else if (!strcmp(name, PAR_ZSTEP)) { *slot = nullptr; *read_only = true; }
  else return false;
  return true;
}

static bool param_valid(const char *name, long v) {
  if (!strcmp(name, PAR_NX)) return v >= 1 && v <= MAX_NX;
  if (!strcmp(name, PAR_NY)) return v >= 1 && v <= MAX_NY;
  if (!strcmp(name, PAR_PITCH))
    return v >= MIN_PITCH_UM && v <= MAX_PITCH_UM && (v * 1000L) % XY_STEP_NM == 0;
  if (!strcmp(name, PAR_SETPOINT)) return v > CONTACT_COUNTS && v <= 4000000L;
  if (!strcmp(name, PAR_MODE)) return v == 0 || v == 1;
  if (!strcmp(name, PAR_LIFT)) return v >= 1 && v <= MAX_LIFT;
  if (!strcmp(name, PAR_SPEED)) return v >= MIN_SPEED && v <= MAX_SPEED;
  if (!strcmp(name, PAR_ACCEL)) return v >= MIN_ACCEL && v <= MAX_ACCEL;
  if (!strcmp(name, PAR_PRESET)) return v >= 0 && v < N_PRESETS;
  return false;
}

static void apply_preset(long p) {
  if (p <= 0 || p >= N_PRESETS) return;
  const Preset &s = PRESETS[p];
  par.nx = s.nx;
  par.ny = s.ny;
  par.pitch = s.pitch;
  par.mode = s.mode;
  par.lift = s.lift;
}

static int scan_fits() {  // 0, or the error number that refuses SS
  if (!homed) return ERR_NOT_HOMED;
  long spp = par.pitch * 1000L / XY_STEP_NM;
  if ((par.nx - 1) * spp > X_TRAVEL_STEPS || (par.ny - 1) * spp > Y_TRAVEL_STEPS)
    return ERR_BAD_ARGUMENT;
  return 0;
}

static int flags() {  // ST's flags: 1 homed, 2/4/8 a switch of x/y/z closed, 16 E-stop open
  int f = 0;
  if (homed) f |= 1;
  if (switch_on(PIN_X_MIN) || switch_on(PIN_X_MAX)) f |= 2;
  if (switch_on(PIN_Y_MIN) || switch_on(PIN_Y_MAX)) f |= 4;
  if (switch_on(PIN_Z_MIN) || switch_on(PIN_Z_MAX)) f |= 8;
  if (estop_input()) f |= 16;
  return f;
}

// Execute one command (tokens in link); the reply is left in `out` (sent by the caller).
static void execute(uint8_t seq) {
  const char *code = link.tokens[1];
  uint8_t nargs = link.ntok - 2;
  const char *a1 = nargs >= 1 ? link.tokens[2] : "";
  bool busy = state == S_SCANNING || state == S_HOMING || state == S_PAUSED;
  long v;
#define REPLY_ERR(n) do { out.begin(seq).word("ER").num(n); return; } while (0)
#define REPLY_OK() out.begin(seq).word("OK").word(code)
  if (!strcmp(code, CMD_IDENTIFY)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    REPLY_OK().word(DEVICE_NAME).num(PROTOCOL_VERSION).word(FIRMWARE_VERSION);
  } else if (!strcmp(code, CMD_GET)) {
    long *slot;
    bool ro;
    if (nargs != 1 || !param_index(a1, &slot, &ro)) REPLY_ERR(ERR_BAD_ARGUMENT);
    REPLY_OK().word(a1).num(ro ? Z_STEP_NM : *slot);
  } else if (!strcmp(code, CMD_SET)) {
    long *slot;
    bool ro;
    if (nargs != 2 || !param_index(a1, &slot, &ro)) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (!parse_long(link.tokens[3], &v)) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (ro) { out.begin(seq).word("ER").num(ERR_BAD_ARGUMENT).word("READONLY"); return; }
    if (!param_valid(a1, v)) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (busy) REPLY_ERR(ERR_BUSY);
    *slot = v;
    REPLY_OK().word(a1).num(v);
  } else if (!strcmp(code, CMD_HOME)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (estop_input()) REPLY_ERR(ERR_ESTOP);
    if (busy) REPLY_ERR(ERR_BUSY);
    estop_flag = false;
    start_home();
    REPLY_OK();
  } else if (!strcmp(code, CMD_START)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (busy) REPLY_ERR(ERR_BUSY);
    if (estop_input()) REPLY_ERR(ERR_ESTOP);
    int e = scan_fits();
    if (e) REPLY_ERR(e);
    start_scan();
    REPLY_OK();
  } else if (!strcmp(code, CMD_PAUSE)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (state != S_SCANNING) REPLY_ERR(ERR_STATE);
    pause_requested = true;
    REPLY_OK();
  } else if (!strcmp(code, CMD_RESUME)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (state != S_PAUSED) REPLY_ERR(ERR_STATE);
    state = S_SCANNING;
    REPLY_OK();
  } else if (!strcmp(code, CMD_ABORT)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (!busy) REPLY_ERR(ERR_STATE);
    bool was_homing = state == S_HOMING;
    stop_all();
    state = S_IDLE;
    pause_requested = false;
    start_after_home = false;
    if (was_homing) homed = false;
    aborted = true;  // ABORTED follows the reply
    REPLY_OK();
  } else if (!strcmp(code, CMD_STATUS)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    REPLY_OK().word(STATE_WORDS[state]).num(row).num(col).num(flags());
  } else if (!strcmp(code, CMD_GAUGE)) {
    if (nargs) REPLY_ERR(ERR_BAD_ARGUMENT);
    if (gauge.count == 0 || millis() - gauge.last_ms > SENSOR_TIMEOUT_MS) REPLY_ERR(ERR_SENSOR);
    REPLY_OK().num(deflection());
  } else if (!strcmp(code, CMD_GETLINE)) {
    if (nargs != 1 || !parse_long(a1, &v)) REPLY_ERR(ERR_BAD_ARGUMENT);
    int8_t s = line_slot(v);
    if (s < 0) REPLY_ERR(ERR_BAD_ARGUMENT);
    for (uint8_t c = 0; c < line_len[s]; c++) send_pixel(v, c, lines[s][c]);
    REPLY_OK().num(v).num(line_len[s]);
  } else {
    REPLY_ERR(ERR_UNKNOWN_COMMAND);
  }
#undef REPLY_ERR
#undef REPLY_OK
}

static void serial_step() {
  LineResult r = link.poll();
  if (r == LINE_NONE) return;
  if (r != LINE_OK) {
    out.begin(0).word("ER").num(r == LINE_CHECKSUM ? ERR_CHECKSUM : ERR_MALFORMED);
    out.send();
    return;
  }
  uint8_t seq = link.seq;
  if (seq == 0) return;  // host stream frames: none for this device, ignored
  if (seq == last_seq && !strcmp(link.body, last_body)) {  // a retry: the same reply again
    memcpy(out.buf, last_reply, last_reply_len + 1);
    out.len = last_reply_len;
    out.send();
    return;
  }
  last_seq = seq;
  strcpy(last_body, link.body);
  aborted = false;
  execute(seq);
  memcpy(last_reply, out.buf, out.len + 1);
  last_reply_len = out.len;
  out.send();
  if (aborted) send_event(EVT_ABORTED);
}

// -- push buttons (closed = LOW), debounced -------------------------------------------------------
static void buttons_step() {
  static uint8_t stable[2] = {HIGH, HIGH}, seen[2] = {HIGH, HIGH};
  static unsigned long since[2] = {0, 0};
  static const uint8_t PINS[2] = {PIN_BTN_START, PIN_BTN_SELECT};
  unsigned long now = millis();
  for (uint8_t i = 0; i < 2; i++) {
    uint8_t v = digitalRead(PINS[i]);
    if (v != seen[i]) { seen[i] = v; since[i] = now; }
    if (v == stable[i] || now - since[i] < 30) continue;
    stable[i] = v;
    if (v != LOW) continue;  // act on the press
    bool busy = state == S_SCANNING || state == S_HOMING || state == S_PAUSED;
    if (i == 1) {
      if (!busy) par.preset = (par.preset + 1) % N_PRESETS;
      continue;
    }
    if (busy || estop_input()) continue;
    apply_preset(par.preset);
    send_event_num(EVT_BUTTON, par.preset);
    if (homed && !scan_fits()) {
      start_scan();
    } else if (!homed) {
      start_after_home = true;
      start_home();
    }
  }
}

// -- status display: no LiquidCrystal in Debian's Arduino core, so two 16-character lines go to a
//    serial 16x2 LCD (SparkFun SerLCD protocol: 0xFE 0x80 / 0xFE 0xC0 place the cursor) on Serial1.
static void display_step() {
  unsigned long now = millis();
  if (now - display_ms < 250) return;
  display_ms = now;
  digitalWrite(PIN_LED, state == S_SCANNING ? HIGH : state == S_FAULT ? ((now >> 8) & 1) : LOW);
  char l1[17], l2[17];
  snprintf(l1, sizeof l1, "%-8s P%ld %s", STATE_WORDS[state], par.preset, homed ? "H" : "-");
  snprintf(l2, sizeof l2, "%3ld,%-3ld z%-7ld", row, col, last_z);
  for (uint8_t i = strlen(l1); i < 16; i++) l1[i] = ' ';
  for (uint8_t i = strlen(l2); i < 16; i++) l2[i] = ' ';
  if (Serial1.availableForWrite() < 36) return;  // never block the scan for the display
  Serial1.write(0xFE); Serial1.write(0x80); Serial1.write((const uint8_t *)l1, 16);
  Serial1.write(0xFE); Serial1.write(0xC0); Serial1.write((const uint8_t *)l2, 16);
}

// -- main -----------------------------------------------------------------------------------------
void setup() {
  pinMode(PIN_ENABLE, OUTPUT);
  digitalWrite(PIN_ENABLE, HIGH);  // drivers off until homing
  axes[0].begin(PIN_X_STEP, PIN_X_DIR);
  axes[1].begin(PIN_Y_STEP, PIN_Y_DIR);
  axes[2].begin(PIN_Z_STEP, PIN_Z_DIR);
  gauge.begin(PIN_HX_DOUT, PIN_HX_SCK);
  const uint8_t inputs[] = {PIN_X_MIN, PIN_X_MAX, PIN_Y_MIN, PIN_Y_MAX, PIN_Z_MIN, PIN_Z_MAX,
                            PIN_BTN_START, PIN_BTN_SELECT, PIN_ESTOP};
  for (uint8_t p : inputs) pinMode(p, INPUT_PULLUP);
  pinMode(PIN_LED, OUTPUT);
  Serial.begin(BAUD_RATE);
  Serial1.begin(9600);
  link.begin();
  PCMSK0 |= _BV(PCINT4);  // the E-stop pin ...
  PCICR |= _BV(PCIE0);    // ... interrupts on any change
  send_event(EVT_BOOT);
  start_tare();
  if (estop_input()) onEstop();
}

void loop() {
  if (estop_flag) {
    estop_flag = false;
    digitalWrite(PIN_ENABLE, HIGH);
    fault(ERR_ESTOP, EVT_ESTOP, nullptr);
  }
  gauge.poll();
  tare_step();
  for (uint8_t i = 0; i < 3; i++) axes[i].run();
  check_limits();
  if (state == S_SCANNING) {
    unsigned long now = millis();
    if (now - gauge.last_ms > SENSOR_TIMEOUT_MS && now - scan_ms > SENSOR_TIMEOUT_MS)
      sensor_fault();
    else scan_step();
  } else if (state == S_HOMING) {
    home_step();
  }
  serial_step();
  buttons_step();
  display_step();
  // Nothing moving: idle until the next interrupt (the 1 ms timer, a received byte, the E-stop).
  // The gauge, buttons and switches are then looked at once a millisecond, which is plenty; it
  // also lets simavr skip the idle cycles, so the emulated scan runs faster than the real one.
  if (all_stopped()) {
    set_sleep_mode(SLEEP_MODE_IDLE);
    sleep_mode();
  }
}
