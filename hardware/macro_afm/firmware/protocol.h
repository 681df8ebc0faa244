// protocol.h: the macroscopic AFM's serial protocol, version 1 (see ../PROTOCOL.md).
// tests/test_hardware_firmware.py parses the #define lines of this file and compares them with
// afmsmiler.hardware.macro.codec (Command, ErrorCode, Event, Param), so the two cannot drift.
// Only these kinds of lines belong here: PROTOCOL_VERSION, CMD_, ERR_, EVT_ and PAR_ defines.
#ifndef MACRO_AFM_PROTOCOL_H
#define MACRO_AFM_PROTOCOL_H

#define PROTOCOL_VERSION 1

// Commands (two uppercase letters)
#define CMD_IDENTIFY "ID"
#define CMD_SET "SP"
#define CMD_GET "GP"
#define CMD_HOME "HM"
#define CMD_START "SS"
#define CMD_PAUSE "PA"
#define CMD_RESUME "RS"
#define CMD_ABORT "AB"
#define CMD_STATUS "ST"
#define CMD_GAUGE "RG"
#define CMD_GETLINE "GL"

// Error numbers (shared by every device of module (h))
#define ERR_CHECKSUM 1
#define ERR_UNKNOWN_COMMAND 2
#define ERR_BAD_ARGUMENT 3
#define ERR_BUSY 4
#define ERR_NOT_HOMED 5
#define ERR_LIMIT 6
#define ERR_ESTOP 7
#define ERR_SENSOR 8
#define ERR_MALFORMED 9
#define ERR_STATE 10

// Events (0 EV <WORD> [ARG])
#define EVT_BOOT "BOOT"
#define EVT_HOMED "HOMED"
#define EVT_DONE "DONE"
#define EVT_PAUSED "PAUSED"
#define EVT_ABORTED "ABORTED"
#define EVT_LIMIT "LIMIT"
#define EVT_ESTOP "ESTOP"
#define EVT_BUTTON "BUTTON"

// Parameters (SP <PAR> <int>, GP <PAR>)
#define PAR_NX "NX"
#define PAR_NY "NY"
#define PAR_PITCH "DX"
#define PAR_ZSTEP "ZS"
#define PAR_SETPOINT "SE"
#define PAR_MODE "MO"
#define PAR_LIFT "LI"
#define PAR_SPEED "VE"
#define PAR_ACCEL "AC"
#define PAR_PRESET "PR"

#endif
