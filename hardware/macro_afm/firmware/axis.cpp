// axis.cpp: trapezoidal step timing after D. Austin, "Generate stepper-motor speed profiles in real
// time", Embedded Systems Programming (2005), the recurrence AccelStepper also uses:
//   c0 = 0.676 sqrt(2 / a) s,   c_n = c_(n-1) - 2 c_(n-1) / (4 n + 1)   (accelerating),
// run backwards (c_(n-1) = c_n + 2 c_n / (4 n - 1)) to decelerate; a move decelerates once its
// remaining steps are no more than the steps taken to reach its speed.
#include "axis.h"

void Axis::begin(uint8_t step_pin, uint8_t dir_pin) {
  step_pin_ = step_pin;
  dir_pin_ = dir_pin;
  pinMode(step_pin_, OUTPUT);
  pinMode(dir_pin_, OUTPUT);
  digitalWrite(step_pin_, LOW);
  setProfile(1000, 10000);
}

void Axis::setProfile(long max_speed, long accel) {
  cmin_ = 1e6f / (float)max_speed;
  c0_ = 0.676f * sqrt(2.0f / (float)accel) * 1e6f;
  if (c0_ < cmin_) c0_ = cmin_;
}

void Axis::moveTo(long target) {
  long delta = target - position;
  if (delta == 0) {
    remaining = 0;
    return;
  }
  dir = delta > 0 ? 1 : -1;
  digitalWrite(dir_pin_, dir > 0 ? HIGH : LOW);
  remaining = delta > 0 ? delta : -delta;
  n_ = 0;
  c_ = c0_;
  last_ = micros() - (unsigned long)c_;  // the first step is due now
}

void Axis::hardStop() {
  remaining = 0;
  n_ = 0;
}

bool Axis::run() {
  if (remaining == 0) return false;
  unsigned long now = micros();
  if (now - last_ < (unsigned long)c_) return true;
  last_ = now;
  digitalWrite(step_pin_, HIGH);
  delayMicroseconds(2);  // A4988 >= 1 us, DRV8825 >= 1.9 us, TB6600 >= 2.5 us at the opto input
  digitalWrite(step_pin_, LOW);
  position += dir;
  remaining--;
  if (remaining == 0) return false;
  if (remaining <= n_) {  // decelerate: as many steps left as it took to speed up
    c_ += 2.0f * c_ / (4.0f * n_ - 1.0f);
    n_--;
  } else if (c_ > cmin_) {  // accelerate
    n_++;
    c_ -= 2.0f * c_ / (4.0f * n_ + 1.0f);
    if (c_ < cmin_) c_ = cmin_;
  }
  return true;
}
