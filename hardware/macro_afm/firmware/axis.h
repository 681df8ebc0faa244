// axis.h: one stepper axis driven by STEP/DIR pulses with a trapezoidal speed profile,
// non-blocking: call run() as often as possible from loop().
#ifndef MACRO_AFM_AXIS_H
#define MACRO_AFM_AXIS_H
#include <Arduino.h>

class Axis {
 public:
  void begin(uint8_t step_pin, uint8_t dir_pin);
  // Maximum rate (steps/s) and acceleration (steps/s^2) of the moves started from now on.
  void setProfile(long max_speed, long accel);
  // Start a move to the absolute position `target` (micro-steps); the axis must be at rest.
  void moveTo(long target);
  void move(long delta) { moveTo(position + delta); }
  // Stop at once (no deceleration): the emergency stop, a limit switch, a switch found by homing.
  void hardStop();
  // Emit the next step if it is due; returns true while the axis moves.
  bool run();
  bool moving() const { return remaining != 0; }
  int8_t direction() const { return dir; }
  long target() const { return position + dir * remaining; }
  volatile long position = 0;  // micro-steps, + = away from the min switch (z: up)

 private:
  uint8_t step_pin_ = 0, dir_pin_ = 0;
  float c0_ = 0, cmin_ = 0;   // first and shortest step interval (us)
  float c_ = 0;               // current step interval (us)
  long n_ = 0;                // index on the acceleration ramp
  long remaining = 0;         // steps left in this move
  int8_t dir = 0;
  unsigned long last_ = 0;    // micros() of the last step
};
#endif
