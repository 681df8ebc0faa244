/* harness.c: run the haptic device's firmware in simavr (ATmega328P, 16 MHz), for tests without
 * the board.
 *
 * What it simulates (pins as in ../haptic.ino):
 *  - UART0 (the protocol link, 1 000 000 baud) as a pseudo-terminal: its path is printed on stdout
 *    as "PTY <path>" so that pyserial opens it like the Uno's USB port;
 *  - the encoder (PD2, PD3): the handle moves to a count given on stdin, one quadrature edge every
 *    20 us (simulated), so the firmware's interrupts count it as they would a turning motor;
 *  - the E-stop switch on PD7 (normally closed to GND: LOW; open = HIGH = pressed);
 *  - the motor: the firmware's PWM set value on OC1A (OCR1A, 10..90 % of ICR1) and its enable pin
 *    PB0 are read back on request.
 * What it does not: the handle's mechanics (the count moves only when told), the amplifier.
 *
 * stdin commands (one per line; each answered by one line on stdout):
 *   COUNT <n>     -> "OK COUNT <n>": move the encoder to count n (edges follow in simulated time)
 *   ESTOP 1|0     -> "OK ESTOP <v>": open (1, pressed) or close (0) the E-stop switch
 *   MOTOR         -> "MOTOR <ocr1a> <icr1> <enable> <sim_us>"
 *   QUIT          -> exit (so does end of file on stdin: it never outlives its parent)
 * Build: ../build.sh (gcc -lsimavr -lutil), with SKIP_HARNESS=1 for the firmware only.
 */
#define _GNU_SOURCE
#include <fcntl.h>
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

static avr_t *avr;
static avr_irq_t *irq_a, *irq_b, *irq_estop, *uart_in;
static int pty_master = -1, uart_xon = 1, enable_level = 0;
static long count = 0, target = 0;
static uint8_t rx_buf[4096], tx_buf[8192];
static size_t rx_head = 0, rx_len = 0, tx_len = 0;
static char in_line[256];
static size_t in_len = 0;
/* quadrature states in order of increasing count: A B = 00, 01, 11, 10 (B leads A), which the
 * firmware counts up (one count per edge, x4 decoding) */
static const int QA[4] = {0, 0, 1, 1}, QB[4] = {0, 1, 1, 0};

static uint8_t ext_d = 0; /* the levels the outside world drives on port D (bits 2, 3, 7) */

static void drive_d(int bit, int level, avr_irq_t *irq) {
  if (level) ext_d |= 1 << bit; else ext_d &= ~(1 << bit);
  /* driven externally: the firmware's pull-ups do not override these pins */
  avr_ioport_external_t e = {.name = 'D', .mask = (1 << 2) | (1 << 3) | (1 << 7),
                             .value = ext_d};
  avr_ioctl(avr, AVR_IOCTL_IOPORT_SET_EXTERNAL('D'), &e);
  avr_raise_irq(irq, level);
}

static void set_encoder(void) {
  int s = (int)(((count % 4) + 4) % 4);
  drive_d(2, QA[s], irq_a);
  drive_d(3, QB[s], irq_b);
}

static avr_cycle_count_t step_encoder(avr_t *a, avr_cycle_count_t when, void *param) {
  (void)a; (void)param;
  if (count != target) {
    count += (target > count) ? 1 : -1;
    set_encoder();
  }
  return when + avr_usec_to_cycles(avr, 20);
}

static void on_enable(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  enable_level = (int)value;
}

static void uart_pump(void) {
  while (uart_xon && rx_len) {
    uint8_t b = rx_buf[rx_head];
    rx_head = (rx_head + 1) % sizeof rx_buf;
    rx_len--;
    avr_raise_irq(uart_in, b);
  }
}

static void on_xon(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)value; (void)param;
  uart_xon = 1;
  uart_pump();
}

static void on_xoff(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)value; (void)param;
  uart_xon = 0;
}

static void on_uart_out(avr_irq_t *irq, uint32_t value, void *param) {
  (void)irq; (void)param;
  if (tx_len < sizeof tx_buf) tx_buf[tx_len++] = (uint8_t)value;
}

static void flush_tx(void) {
  size_t done = 0;
  while (done < tx_len) {
    ssize_t n = write(pty_master, tx_buf + done, tx_len - done);
    if (n <= 0) break;
    done += (size_t)n;
  }
  memmove(tx_buf, tx_buf + done, tx_len - done);
  tx_len -= done;
}

static void command(char *line) {
  char a[32] = "";
  long v = 0;
  int n = sscanf(line, "%31s %ld", a, &v);
  if (n < 1) return;
  if (!strcmp(a, "COUNT") && n == 2) {
    target = v;
    printf("OK COUNT %ld\n", v);
  } else if (!strcmp(a, "ESTOP") && n == 2) {
    drive_d(7, v ? 1 : 0, irq_estop);
    printf("OK ESTOP %ld\n", v);
  } else if (!strcmp(a, "MOTOR")) {
    /* ATmega328P: OCR1A at 0x88 (low) / 0x89, ICR1 at 0x86 / 0x87 */
    unsigned ocr = avr->data[0x88] | (avr->data[0x89] << 8);
    unsigned icr = avr->data[0x86] | (avr->data[0x87] << 8);
    printf("MOTOR %u %u %d %llu\n", ocr, icr, enable_level,
           (unsigned long long)avr_cycles_to_usec(avr, avr->cycle));
  } else if (!strcmp(a, "QUIT")) {
    exit(0);
  } else {
    printf("ERR %s\n", a);
  }
  fflush(stdout);
}

static void read_stdin(void) {
  char buf[256];
  ssize_t n = read(0, buf, sizeof buf);
  if (n == 0) exit(0); /* the parent has gone */
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

static void no_sleep(avr_t *a, avr_cycle_count_t howlong) { (void)a; (void)howlong; }

int main(int argc, char **argv) {
  const char *elf = NULL;
  double realtime = 1.0;
  signal(SIGPIPE, SIG_IGN);
  for (int i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--realtime") && i + 1 < argc) realtime = atof(argv[++i]);
    else elf = argv[i];
  }
  if (!elf) {
    fprintf(stderr, "usage: harness haptic.elf [--realtime FACTOR (0: as fast as possible)]\n");
    return 2;
  }
  fflush(stdout);
  int saved_stdout = dup(1);
  dup2(2, 1); /* simavr's loader talks on stdout */
  elf_firmware_t fw;
  memset(&fw, 0, sizeof fw);
  if (elf_read_firmware(elf, &fw)) { fprintf(stderr, "cannot read %s\n", elf); return 2; }
  strcpy(fw.mmcu, "atmega328p");
  fw.frequency = 16000000;
  avr = avr_make_mcu_by_name(fw.mmcu);
  if (!avr) { fprintf(stderr, "no atmega328p in this simavr\n"); return 2; }
  avr_init(avr);
  avr->log = 0;
  avr_load_firmware(avr, &fw);
  avr->frequency = 16000000;
  avr->sleep = no_sleep;
  fflush(stdout);
  dup2(saved_stdout, 1);
  close(saved_stdout);

  irq_a = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('D'), 2);
  irq_b = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('D'), 3);
  irq_estop = avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('D'), 7);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_IOPORT_GETIRQ('B'), 0), on_enable, NULL);
  set_encoder();
  drive_d(7, 0, irq_estop); /* the E-stop switch closed */
  avr_cycle_timer_register(avr, avr_usec_to_cycles(avr, 20), step_encoder, NULL);

  uint32_t flags = 0;
  avr_ioctl(avr, AVR_IOCTL_UART_GET_FLAGS('0'), &flags);
  flags &= ~(AVR_UART_FLAG_STDIO | AVR_UART_FLAG_POLL_SLEEP);
  avr_ioctl(avr, AVR_IOCTL_UART_SET_FLAGS('0'), &flags);
  uart_in = avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_INPUT);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUTPUT),
                          on_uart_out, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XON),
                          on_xon, NULL);
  avr_irq_register_notify(avr_io_getirq(avr, AVR_IOCTL_UART_GETIRQ('0'), UART_IRQ_OUT_XOFF),
                          on_xoff, NULL);

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

  struct timespec t0;
  clock_gettime(CLOCK_MONOTONIC, &t0);
  for (;;) {
    for (int i = 0; i < 2000; i++) {
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
