// hx711.h: the HX711 load-cell amplifier read by bit-banging DOUT/PD_SCK, without blocking:
// poll() reads a conversion only when DOUT is low (data ready), channel A at gain 128.
#ifndef MACRO_AFM_HX711_H
#define MACRO_AFM_HX711_H
#include <Arduino.h>

class HX711 {
 public:
  void begin(uint8_t dout, uint8_t sck);
  bool poll();                 // true when a new reading arrived
  long value = 0;              // last reading, signed 24-bit counts
  unsigned long count = 0;     // readings so far
  unsigned long last_ms = 0;   // millis() of the last reading
 private:
  uint8_t dout_ = 0, sck_ = 0;
};
#endif
