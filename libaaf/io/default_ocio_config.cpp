#include "default_ocio_config.h"

namespace aaf::io {

const char *const kDefaultOcioConfig = R"(ocio_profile_version: 2
name: aaf-default
description: Fallback config of the aaf tool (linear Rec.709 to an sRGB display)
search_path: ""
strictparsing: true
luma: [0.2126, 0.7152, 0.0722]

roles:
  default: Linear Rec.709
  scene_linear: Linear Rec.709
  data: Raw

displays:
  sRGB:
    - !<View> {name: Standard, colorspace: sRGB Encoded}
    - !<View> {name: Raw, colorspace: Raw}

active_displays: [sRGB]
active_views: [Standard, Raw]

colorspaces:
  - !<ColorSpace>
    name: Linear Rec.709
    family: Linear
    encoding: scene-linear
    isdata: false
    description: Scene-linear light with the Rec.709 (sRGB) primaries and white

  - !<ColorSpace>
    name: sRGB Encoded
    family: Display
    encoding: sdr-video
    isdata: false
    description: Rec.709 primaries with the sRGB transfer function
    from_scene_reference: !<ExponentWithLinearTransform> {gamma: 2.4, offset: 0.055, direction: inverse}

  - !<ColorSpace>
    name: Raw
    family: Data
    encoding: data
    isdata: true
    description: Values passed through unchanged
)";

}  // namespace aaf::io
