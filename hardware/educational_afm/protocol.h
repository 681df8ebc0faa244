// The educational AFM's serial protocol (device EDUAFM): codes shared with the Python codec
// (afmsmiler/hardware/educational/codec.py); a test parses this file and compares.
#pragma once

#define PROTOCOL_VERSION 1

#define CMD_IDENTIFY "ID"
#define CMD_SET "SP"
#define CMD_GET "GP"
#define CMD_START "SS"
#define CMD_ABORT "AB"
#define CMD_STATUS "ST"
#define CMD_GETLINE "GL"

#define PAR_NX "NX"
#define PAR_NY "NY"
#define PAR_PITCH "DX"
#define PAR_ZSTEP "ZS"
#define PAR_SETPOINT "SE"

#define EVT_BOOT "BOOT"
#define EVT_DONE "DONE"
#define EVT_ABORTED "ABORTED"
#define EVT_FAULT "FAULT"

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
