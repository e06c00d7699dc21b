#pragma once
// `rangefit watch`: prints detections, lifecycle states, cloud sizes and diagnostics of a running
// rangefitd as they arrive (one JSON object per line).
