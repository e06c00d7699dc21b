#pragma once
// `rangefit request bore|object ...`: a DDS client for operators and scripts. Sends a
// DetectRequest to rangefitd and waits for its Detection; prints it as JSON.
