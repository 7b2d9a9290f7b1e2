// Reading and writing linear float images as OpenEXR.
#pragma once
#include "core/image.h"
#include <string>
#include <vector>

namespace bmfr {

/// What a read fills in: the pixels, or only the sizes (width, height, channels; no pixel
/// storage), which checks a file's header, channels and completeness without decompressing it.
enum class ExrContent { Pixels, Header };

/// Reads an EXR as `channels` floats per pixel (3: R,G,B; 2: R,G; 1: Y, R or the only
/// channel; never invented from fewer). Throws bmfr::Error naming the file when it is missing,
/// unreadable, empty or lacks the channels.
///
/// Multilayer and multi-part files (as Blender writes them): `layer` names the channel set, as
/// in "ViewLayer.Denoising Albedo" for the channels "ViewLayer.Denoising Albedo.R/G/B"; X,Y,Z
/// stand in for R,G,B and V or Z for a single channel. In a multi-part file a part's name is
/// the layer prefix of its channels.
ImageF readExr(const std::string& path, int channels, const std::string& layer = "",
               ExrContent content = ExrContent::Pixels);

/// Every channel of an EXR by its full name (part name prefixed in multi-part files).
std::vector<std::string> exrChannelNames(const std::string& path);

/// One image wanted from a file: its layer ("" = the plain channels) and channel count.
struct ExrLayerRead {
    std::string layer;
    int channels = 3;
    ImageF* out = nullptr;
};

/// Reads several layers of one file in one pass over each part's pixels (a multilayer frame
/// holds every buffer: decompressing it once per buffer would multiply the cost). Same rules and
/// errors as readExr.
void readExrLayers(const std::string& path, const std::vector<ExrLayerRead>& reads,
                   ExrContent content = ExrContent::Pixels);

/// findExrLayer over a channel list already read (exrChannelNames); `path` names the file in
/// errors.
std::string findExrLayer(const std::vector<std::string>& channelNames, const std::string& pass,
                         const std::string& path);

/// The layer of `path` that holds `pass` (a name such as "Combined" or "Denoising Albedo"):
/// a channel set named `pass` or ending in "." + pass. Empty when there is none; an error when
/// several view layers hold it (say which with a layer name).
std::string findExrLayer(const std::string& path, const std::string& pass);

/// Whether a file has channels outside any layer (no '.' in the name), as a plain RGB EXR.
bool hasPlainChannels(const std::vector<std::string>& channelNames);

/// Whether `layer` is the pass `pass` ("Vector") itself or under a view layer ("ViewLayer.Vector").
bool isLayerOfPass(const std::string& layer, const std::string& pass);

/// The layer an image viewer shows of `path`: "" when it has plain channels, else the layer of
/// its Combined pass (a Blender multilayer render). Throws bmfr::Error listing the layers when
/// it has neither.
std::string imageLayer(const std::string& path);

/// Writes 1, 2 or 3-channel float images (Y / R,G / R,G,B) atomically (temp file + rename).
void writeExr(const std::string& path, const ImageF& image);

} // namespace bmfr
