// config.h: the haptic device's identity, its serial speed and its status flags.
#ifndef HAPTIC_CONFIG_H
#define HAPTIC_CONFIG_H

#define DEVICE_NAME "HAPTIC"
#define FIRMWARE_VERSION "0.1.0"
#define BAUD_RATE 1000000

// status flags (OK ST <state> <flags> <position um> <force uN>), cleared by each ST
#define FLAG_SATURATED 1
#define FLAG_WATCHDOG 2
#define FLAG_LIMIT 4
#define FLAG_ESTOP 8

#endif
