#pragma once
// `rangefit replay SPOOL_ENTRY`: re-runs the detection of a spooled scan offline, with the
// detection parameters and object models of a daemon config, and prints old and new results.
