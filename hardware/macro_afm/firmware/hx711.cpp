// hx711.cpp: HX711 datasheet (Avia Semiconductor, rev. 2.0): DOUT low = a conversion is ready; 24
// PD_SCK pulses shift it out MSB first (two's complement), a 25th pulse selects channel A, gain
// 128 for the next one. PD_SCK must not stay high for 60 us (power down): no interrupts while high.
#include "hx711.h"

void HX711::begin(uint8_t dout, uint8_t sck) {
  dout_ = dout;
  sck_ = sck;
  pinMode(dout_, INPUT);
  pinMode(sck_, OUTPUT);
  digitalWrite(sck_, LOW);
}

bool HX711::poll() {
  if (digitalRead(dout_) != LOW) return false;
  unsigned long raw = 0;
  for (uint8_t i = 0; i < 25; i++) {
    uint8_t sreg = SREG;
    cli();
    digitalWrite(sck_, HIGH);
    delayMicroseconds(1);
    uint8_t bit = digitalRead(dout_);
    digitalWrite(sck_, LOW);
    SREG = sreg;
    if (i < 24) raw = (raw << 1) | bit;
  }
  if (raw & 0x800000UL) raw |= 0xFF000000UL;  // sign-extend 24 -> 32 bits
  value = (long)raw;
  count++;
  last_ms = millis();
  return true;
}
