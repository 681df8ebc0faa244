/* harness.c: run the macroscopic AFM's firmware in simavr (ATmega2560, 16 MHz) against a virtual
 * machine, for tests without the board.
 *
 * What it simulates (pins as in ../firmware/config.h):
 *  - UART0 (the protocol link) as a pseudo-terminal: its path is printed on stdout as "PTY <path>"
 *    so that pyserial (or any terminal) opens it like the board's USB port;
 *  - the three step/dir drivers: STEP rising edges are counted with the DIR level (and ignored
 *    while ENABLE is high), giving the x, y, z positions in micro-steps;
 *  - the limit switches at the axis ends (closed = LOW): X_MIN when x <= 0, X_MAX when x >= the
 *    x travel, Y likewise, Z_MAX (top, home) when z >= the z top, Z_MIN (bed) when z <= 0;
 *  - the HX711: DOUT goes low every 1/rate s with a new conversion, which the PD_SCK pulses shift
 *    out MSB first; its value is offset + gain * deflection (+ Gaussian noise), the deflection
 *    being the needle's interference with the virtual sample (rigid: the ruler bends by it);
 *  - the E-stop (NC switch, open = HIGH) and the two push buttons, on request (stdin);
 *  - UART1 (the serial 16x2 status display) kept as the display's two lines.
 *  - optionally (--catch UM), the friction that spoils contact mode on tall samples: a needle on
 *    the surface that meets a wall taller than UM while the carriage moves sideways stays caught
 *    behind it (the ruler bends sideways) until it is lifted off the surface.
 * What it does not: motor dynamics (steps are exact, no lost steps, no inertia), the ruler's
 * vibration (6 Hz), friction on gentle slopes, the HX711's settling and power-down, electrical
 * noise on inputs.
 *
 * The virtual sample (--map FILE) is a text file:
 *     # comment lines
 *     macro_afm_map 1
 *     <nx> <ny> <pitch_um>
 *     <ny lines of nx heights in um, row 0 first (y = 0), columns along x>
 * Pixel (i, j) is the square of side pitch centred at (origin_x + i pitch, origin_y + j pitch);
 * outside the map the surface is the bed (height 0). Positions: x, y micro-steps of 12.5 um, z
 * micro-steps of 2.5 um, the needle's tip at z * 2.5 um above the bed.
 *
 * stdin commands (one per line; each answered by one line on stdout):
 *   POS                  -> "POS <x> <y> <z> <sim_us> <caught>" (micro-steps, simulated us,
 *                           1 if the needle is caught on a wall)
 *   ORIGIN               -> put the map's pixel (0, 0) at the current x, y ("OK ORIGIN x y")
 *   ESTOP 1|0            -> open (1: emergency stop) or close (0) the E-stop switch
 *   BUTTON START|SELECT  -> press the button for 100 ms (simulated)
 *   FORCE <SWITCH> 1|0|-1 -> force a limit switch (X_MIN ... Z_MAX) closed, open, or back to auto
 *   GAUGE 0|1            -> disconnect (0) or reconnect (1) the HX711 (DOUT stays high)
 *   DISPLAY              -> "DISPLAY <line 1>|<line 2>"
 *   QUIT                 -> exit (so does end of file on stdin: it never outlives its parent)
 * Build: ../build.sh (gcc -lsimavr -lutil).
 */
#define _GNU_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <poll.h>
#include <pty.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <termios.h>
#include <time.h>
#include <unistd.h>

#include <sim_avr.h>
#include <sim_elf.h>
#include <sim_time.h>
#include <sim_cycle_timers.h>
#include <avr_ioport.h>
#include <avr_uart.h>

#define XY_STEP_UM 12.5
#define Z_STEP_UM 2.5

enum { SW_X_MIN, SW_X_MAX, SW_Y_MIN, SW_Y_MAX, SW_Z_MIN, SW_Z_MAX, N_SW };
static const char *SW_NAMES[N_SW] = {"X_MIN", "X_MAX", "Y_MIN", "Y_MAX", "Z_MIN", "Z_MAX"};
static const int SW_BIT[N_SW] = {5, 4, 3, 2, 1, 0}; /* port C */

static avr_t *avr;
static long pos[3];                       /* x, y, z micro-steps */
static int dir_level[3], step_level[3], enable_level = 1;
static int sw_state[N_SW], sw_force[N_SW] = {-1, -1, -1, -1, -1, -1};
static long x_max_steps, y_max_steps, z_top_steps;
static avr_irq_t *irq_c[8], *irq_estop, *irq_btn[2];
static uint8_t ext_c = 0xFF, ext_b = 0xFF, ext_l = 0xFF; /* external levels of ports C, B, L */

/* virtual sample */
static int map_nx, map_ny;
static double map_pitch_um = 1, *map_h;
static double origin_x_um, origin_y_um;
static double gain = 12.0, offset = 100000.0, noise = 0.0, catch_um = 0.0;
static unsigned rng_state = 12345;

/* HX711 */
static avr_cycle_count_t hx_period;
static int hx_ready, hx_bits, hx_sck, hx_dead;
static uint32_t hx_word;

/* UART0 <-> pty */
static int pty_master = -1;
static avr_irq_t *uart_in;
static int uart_xon;
static uint8_t rx_buf[4096];
static size_t rx_head, rx_len;
static uint8_t tx_buf[8192];
static size_t tx_len;

/* UART1: the status display */
static char display[2][17];
static int disp_line, disp_col, disp_cmd;

/* simavr's default sleep callback sleeps in real time; skip the firmware's idle time instead
   (--realtime paces the whole run, see main) */
static void no_sleep(avr_t *a, avr_cycle_count_t how_long) { (void)a; (void)how_long; }

static double uniform(void) {
  rng_state = rng_state * 1103515245u + 12345u;
  return ((rng_state >> 8) & 0xFFFFFF) / 16777216.0 + 1e-9;
}

static double gaussian(void) {
  return sqrt(-2.0 * log(uniform())) * cos(2 * M_PI * uniform());
}

static double surface_at(double x_um, double y_um) {
  if (!map_h) return 0;
  long i = lround((x_um - origin_x_um) / map_pitch_um);
  long j = lround((y_um - origin_y_um) / map_pitch_um);
  if (i < 0 || j < 0 || i >= map_nx || j >= map_ny) return 0;
  return map_h[j * map_nx + i];
}

/* Where the needle is: with the carriage, unless it caught on a wall (--catch) */
static int caught;
static double needle_x_um, needle_y_um;

static double surface_um(void) { return surface_at(needle_x_um, needle_y_um); }

static double deflection_um(void) {
  double d = surface_um() - pos[2] * Z_STEP_UM;
  return d > 0 ? d : 0;
}

/* After every step: a needle on the surface that meets a wall taller than catch_um while the
   carriage moves sideways stays behind it (the ruler bends sideways), until it is lifted off. */
static void move_needle(int lateral) {
  double cx = pos[0] * XY_STEP_UM, cy = pos[1] * XY_STEP_UM;
  if (caught) {
    if (deflection_um() > 0) return;
    caught = 0;  /* lifted off: the ruler springs back over the carriage */
  } else if (lateral && catch_um > 0 && deflection_um() > 0 &&
             surface_at(cx, cy) - surface_um() > catch_um) {
    caught = 1;
    return;
  }
  needle_x_um = cx;
  needle_y_um = cy;
}

/* -- inputs ------------------------------------------------------------------------------------ */
static void set_external(char port, uint8_t value) {
  avr_ioport_external_t e = {.name = port, .mask = 0xFF, .value = value};
  avr_ioctl(avr, AVR_IOCTL_IOPORT_SET_EXTERNAL(port), &e);
}

static void drive_c(int bit, int level) {
  if (level) ext_c |= 1 << bit; else ext_c &= ~(1 << bit);
  set_external('C', ext_c);
  avr_raise_irq(irq_c[bit], level);
}

static void update_switches(void) {
  int on[N_SW] = {pos[0] <= 0, pos[0] >= x_max_steps, pos[1] <= 0, pos[1] >= y_max_steps,
                  pos[2] <= 0, pos[2] >= z_top_steps};
  for (int s = 0; s < N_SW; s++) {
    int v = sw_force[s] >= 0 ? sw_force[s] : on[s];
    if (v != sw_state[s]) {
      sw_state[s] = v;
      drive_c(SW_BIT[s], !v); /* closed switch pulls the pin LOW */
    }
  }
}

static void set_estop(int open) {
  if (open) ext_b |= 1 << 4; else ext_b &= ~(1 << 4);
  set_external('B', ext_b);
  avr_raise_irq(irq_estop, open ? 1 : 0);
}

static void set_button(int i, int pressed) {
  int bit = 7 - i;
  if (pressed) ext_l &= ~(1 << bit); else ext_l |= 1 << bit;
  set_external('L', ext_l);
  avr_raise_irq(irq_btn[i], pressed ? 0 : 1);
}

static avr_cycle_count_t release_button(avr_t *a, avr_cycle_count_t when, void *param) {
  (void)a; (void)when;
  set_button((int)(intptr_t)param, 0);
  return 0;
}

/* -- steppers ---------------------------------------------------------------------------------- */
static void on_port_a(avr_irq_t *irq, uint32_t value, void *param) {
  (void)param;
  int bit = irq->irq;
  int v = value & 1;
  if (bit == 6) { enable_level = v; return; }
  if (bit > 6) return;
  int axis = bit / 2;
  if (bit & 1) { dir_level[axis] = v; return; }
  if (v && !step_level[axis] && !enable_level) {
    pos[axis] += dir_level[axis] ? 1 : -1;
    move_needle(axis < 2);
    update_switches();
  }
  step_level[axis] = v;
}

/* -- HX711 ------------------------------------------------------------------------------------- */
static avr_cycle_count_t hx_convert(avr_t *a, avr_cycle_count_t when, void *param) {
  (void)a; (void)param;
  if (hx_dead) { /* unplugged: DOUT floats high (the module's pull-up), no conversions */
    drive_c(7, 1);
    hx_ready = 0;
    return when + hx_period;
  }
  if (hx_bits == 0 || hx_bits >= 25) { /* not in the middle of a read-out */
    double v = offset + gain * deflection_um() + (noise > 0 ? noise * gaussian() : 0);
    long c = lround(v);
    if (c > 0x7FFFFF) c = 0x7FFFFF;
    if (c < -0x800000) c = -0x800000;
    hx_word = (uint32_t)c & 0xFFFFFF;
    hx_bits = 0;
    hx_ready = 1;
    drive_c(7, 0);
  }
  return when + hx_period;
}

static void on_sck(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  int v = value & 1;
  if (v && !hx_sck && hx_ready) { /* rising edge: the next bit on DOUT */
    hx_bits++;
    if (hx_bits <= 24) drive_c(7, (hx_word >> (24 - hx_bits)) & 1);
    else { drive_c(7, 1); hx_ready = 0; }  /* 25th pulse: gain 128, DOUT high until the next */
  }
  hx_sck = v;
}

/* -- UARTs ------------------------------------------------------------------------------------- */
static void uart_pump(void) {
  while (uart_xon && rx_len) {
    uint8_t b = rx_buf[rx_head];
    rx_head = (rx_head + 1) % sizeof rx_buf;
    rx_len--;
    avr_raise_irq(uart_in, b);
  }
}

static void on_uart_xon(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)value; (void)param;
  uart_xon = 1;
  uart_pump();
}

static void on_uart_xoff(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)value; (void)param;
  uart_xon = 0;
}

static void on_uart_out(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  if (tx_len < sizeof tx_buf) tx_buf[tx_len++] = (uint8_t)value;
}

static void on_uart1_out(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  uint8_t b = (uint8_t)value;
  if (disp_cmd) { /* SerLCD: 0xFE then an HD44780 command; 0x80 | addr sets the cursor */
    disp_cmd = 0;
    if (b & 0x80) { disp_line = (b & 0x40) ? 1 : 0; disp_col = b & 0x0F; }
    return;
  }
  if (b == 0xFE) { disp_cmd = 1; return; }
  if (b >= 0x20 && b < 0x7F && disp_col < 16) display[disp_line][disp_col++] = (char)b;
}

static void flush_tx(void) { /* what the pty does not take now waits (up to 8 KB) */
  size_t done = 0;
  while (done < tx_len) {
    ssize_t n = write(pty_master, tx_buf + done, tx_len - done);
    if (n <= 0) break;
    done += (size_t)n;
  }
  memmove(tx_buf, tx_buf + done, tx_len - done);
  tx_len -= done;
}

/* -- stdin commands ---------------------------------------------------------------------------- */
static void command(char *line) {
  char a[32] = "", b[32] = "";
  int n = sscanf(line, "%31s %31s", a, b);
  if (n < 1) return;
  if (!strcmp(a, "POS")) {
    printf("POS %ld %ld %ld %llu %d\n", pos[0], pos[1], pos[2],
           (unsigned long long)avr_cycles_to_usec(avr, avr->cycle), caught);
  } else if (!strcmp(a, "ORIGIN")) {
    origin_x_um = pos[0] * XY_STEP_UM;
    origin_y_um = pos[1] * XY_STEP_UM;
    printf("OK ORIGIN %ld %ld\n", pos[0], pos[1]);
  } else if (!strcmp(a, "ESTOP") && n == 2) {
    set_estop(atoi(b) != 0);
    printf("OK ESTOP %d\n", atoi(b) != 0);
  } else if (!strcmp(a, "BUTTON") && n == 2 && (!strcmp(b, "START") || !strcmp(b, "SELECT"))) {
    int i = !strcmp(b, "START") ? 0 : 1;
    set_button(i, 1);
    avr_cycle_timer_register_usec(avr, 100000, release_button, (void *)(intptr_t)i);
    printf("OK BUTTON %s\n", b);
  } else if (!strcmp(a, "FORCE")) {
    char c[8] = "";
    int s;
    if (sscanf(line, "%*s %31s %7s", b, c) != 2) { printf("ERR usage\n"); fflush(stdout); return; }
    for (s = 0; s < N_SW && strcmp(SW_NAMES[s], b); s++) {}
    if (s == N_SW) { printf("ERR bad switch\n"); fflush(stdout); return; }
    sw_force[s] = atoi(c) < 0 ? -1 : atoi(c) != 0;
    update_switches();
    printf("OK FORCE %s %d\n", b, sw_force[s]);
  } else if (!strcmp(a, "GAUGE") && n == 2) {
    hx_dead = atoi(b) == 0;
    printf("OK GAUGE %d\n", !hx_dead);
  } else if (!strcmp(a, "DISPLAY")) {
    printf("DISPLAY %s|%s\n", display[0], display[1]);
  } else if (!strcmp(a, "QUIT")) {
    printf("OK QUIT\n");
    fflush(stdout);
    exit(0);
  } else {
    printf("ERR unknown command\n");
  }
  fflush(stdout);
}

static char in_line[256];
static size_t in_len;

static void read_stdin(void) {
  char buf[256];
  ssize_t n = read(0, buf, sizeof buf);
  if (n == 0) exit(0); /* parent gone */
  if (n < 0) return;
  for (ssize_t i = 0; i < n; i++) {
    if (buf[i] == '\n') {
      in_line[in_len] = 0;
      command(in_line);
      in_len = 0;
    } else if (in_len < sizeof in_line - 1) {
      in_line[in_len++] = buf[i];
    }
  }
}

static void read_pty(void) {
  uint8_t buf[256];
  ssize_t n = read(pty_master, buf, sizeof buf);
  for (ssize_t i = 0; i < n && rx_len < sizeof rx_buf; i++) {
    rx_buf[(rx_head + rx_len) % sizeof rx_buf] = buf[i];
    rx_len++;
  }
  uart_pump();
}

/* -- setup ------------------------------------------------------------------------------------- */
static void load_map(const char *path) {
  FILE *f = fopen(path, "r");
  if (!f) { perror(path); exit(2); }
  char line[4096];
  int version = 0, header = 0;
  long k = 0;
  while (fgets(line, sizeof line, f)) {
    if (line[0] == '#') continue;
    if (!version) {
      if (sscanf(line, "macro_afm_map %d", &version) != 1 || version != 1) {
        fprintf(stderr, "%s: not a macro_afm_map 1 file\n", path);
        exit(2);
      }
      continue;
    }
    if (!header) {
      if (sscanf(line, "%d %d %lf", &map_nx, &map_ny, &map_pitch_um) != 3 || map_nx <= 0 ||
          map_ny <= 0 || map_nx > 4096 || map_ny > 4096 || map_pitch_um <= 0) {
        fprintf(stderr, "%s: bad header\n", path);
        exit(2);
      }
      map_h = calloc((size_t)map_nx * map_ny, sizeof *map_h);
      header = 1;
      continue;
    }
    char *p = line, *end;
    for (;;) {
      double v = strtod(p, &end);
      if (end == p) break;
      if (k < (long)map_nx * map_ny) map_h[k++] = v;
      p = end;
    }
  }
  fclose(f);
  if (!header || k != (long)map_nx * map_ny) {
    fprintf(stderr, "%s: expected %d x %d heights, got %ld\n", path, map_nx, map_ny, k);
    exit(2);
  }
}

static void usage(void) {
  fprintf(stderr,
          "usage: harness FIRMWARE.elf [--map FILE] [--gain COUNTS_PER_UM] [--offset COUNTS]\n"
          "  [--noise COUNTS] [--rate SPS] [--seed N] [--x-max MM] [--y-max MM] [--z-top MM]\n"
          "  [--catch UM]\n"
          "  [--start X,Y,Z (mm)] [--origin X,Y (mm)] [--realtime FACTOR]\n");
  exit(2);
}

int main(int argc, char **argv) {
  const char *elf = NULL, *map = NULL;
  double rate = 80, x_max = 200, y_max = 200, z_top = 10, realtime = 0;
  double start[3] = {2, 2, 8};
  signal(SIGPIPE, SIG_IGN);
  for (int i = 1; i < argc; i++) {
    const char *o = argv[i];
    if (o[0] != '-') { elf = o; continue; }
    if (i + 1 >= argc) usage();
    const char *v = argv[++i];
    if (!strcmp(o, "--map")) map = v;
    else if (!strcmp(o, "--gain")) gain = atof(v);
    else if (!strcmp(o, "--offset")) offset = atof(v);
    else if (!strcmp(o, "--noise")) noise = atof(v);
    else if (!strcmp(o, "--catch")) catch_um = atof(v);
    else if (!strcmp(o, "--rate")) rate = atof(v);
    else if (!strcmp(o, "--seed")) rng_state = (unsigned)atol(v);
    else if (!strcmp(o, "--x-max")) x_max = atof(v);
    else if (!strcmp(o, "--y-max")) y_max = atof(v);
    else if (!strcmp(o, "--z-top")) z_top = atof(v);
    else if (!strcmp(o, "--realtime")) realtime = atof(v);
    else if (!strcmp(o, "--start")) {
      if (sscanf(v, "%lf,%lf,%lf", &start[0], &start[1], &start[2]) != 3) usage();
    } else if (!strcmp(o, "--origin")) {
      if (sscanf(v, "%lf,%lf", &origin_x_um, &origin_y_um) != 2) usage();
      origin_x_um *= 1000;
      origin_y_um *= 1000;
    } else usage();
  }
  if (!elf || rate <= 0 || rate > 1000) usage();
  if (map) load_map(map);
  x_max_steps = lround(x_max * 1000 / XY_STEP_UM);
  y_max_steps = lround(y_max * 1000 / XY_STEP_UM);
  z_top_steps = lround(z_top * 1000 / Z_STEP_UM);
  pos[0] = lround(start[0] * 1000 / XY_STEP_UM);
  pos[1] = lround(start[1] * 1000 / XY_STEP_UM);
  pos[2] = lround(start[2] * 1000 / Z_STEP_UM);
  needle_x_um = pos[0] * XY_STEP_UM;
  needle_y_um = pos[1] * XY_STEP_UM;

  /* simavr's loader talks on stdout: keep stdout for our protocol ("PTY ...", replies) */
  fflush(stdout);
  int saved_stdout = dup(1);
  dup2(2, 1);
  elf_firmware_t fw;
  memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(elf, &fw)) { fprintf(stderr, "cannot read %s\n", elf); return 2; }
  strcpy(fw.mmcu, "atmega2560");
  fw.frequency = 16000000;
  avr = avr_make_mcu_by_name(fw.mmcu);
  if (!avr) { fprintf(stderr, "no atmega2560 in this simavr\n"); return 2; }
  avr_init(avr);
  avr->log = 0;
  avr_load_firmware(avr, &fw);
  avr->frequency = 16000000;
  avr->sleep = no_sleep;
  fflush(stdout);
  dup2(saved_stdout, 1);
  close(saved_stdout);

  /* pins */
  for (int b = 0; b < 8; b++) {
    avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('A'), b), on_port_a, NULL);
    irq_c[b] = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('C'), b);
  }
  avr_irq_register_notify(irq_c[6], on_sck, NULL);
  irq_estop = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 4);
  irq_btn[0] = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('L'), 7);
  irq_btn[1] = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('L'), 6);
  for (int s = 0; s < N_SW; s++) sw_state[s] = -1;
  update_switches();
  drive_c(7, 1); /* HX711 busy until the first conversion */
  set_estop(0);
  set_button(0, 0);
  set_button(1, 0);
  hx_period = avr_usec_to_cycles(avr, (uint32_t)(1e6 / rate));
  avr_cycle_timer_register(avr, hx_period, hx_convert, NULL);

  /* UART0 <-> pty, UART1 -> display */
  uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~(AVR_UART_FLAG_STDIO | AVR_UART_FLAG_POLL_SLEEP);
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('1'), &flags);
  flags &= ~(AVR_UART_FLAG_STDIO | AVR_UART_FLAG_POLL_SLEEP);
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('1'), &flags);
  uart_in = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          on_uart_out, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON),
                          on_uart_xon, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                          on_uart_xoff, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('1'), UART_IRQ_OUTPUT),
                          on_uart1_out, NULL);
  memset(display, ' ', sizeof display);
  display[0][16] = display[1][16] = 0;

  int slave;
  char name[256];
  struct termios tio;
  if (openpty(&pty_master, &slave, name, NULL, NULL) < 0) { perror("openpty"); return 2; }
  tcgetattr(slave, &tio);
  cfmakeraw(&tio);
  tcsetattr(slave, TCSANOW, &tio);
  fcntl(pty_master, F_SETFL, fcntl(pty_master, F_GETFL) | O_NONBLOCK);
  fcntl(0, F_SETFL, fcntl(0, F_GETFL) | O_NONBLOCK);
  printf("PTY %s\n", name);
  fflush(stdout);
  /* keep `slave` open: the master then never sees a hang-up while no host has the port open */

  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (;;) {
    for (int i = 0; i < 4000; i++) {
      int st = avr_run(avr);
      if (st == cpu_Done || st == cpu_Crashed) {
        fprintf(stderr, "firmware stopped (state %d)\n", st);
        return 1;
      }
    }
    if (tx_len) flush_tx();
    struct pollfd fds[2] = {{.fd = 0, .events = POLLIN}, {.fd = pty_master, .events = POLLIN}};
    int timeout = 0;
    if (realtime > 0) { /* no faster than `realtime` x real time */
      struct timespec t;
      clock_gettime(CLOCK_MONOTONIC, &t);
      double wall = (t.tv_sec - t0.tv_sec) + (t.tv_nsec - t0.tv_nsec) * 1e-9;
      double sim = avr->cycle / 16e6 / realtime;
      if (sim > wall) timeout = (int)((sim - wall) * 1000) + 1;
    }
    if (poll(fds, 2, timeout) > 0) {
      if (fds[0].revents & (POLLIN | POLLHUP)) read_stdin();
      if (fds[1].revents & POLLIN) read_pty();
    }
  }
}
