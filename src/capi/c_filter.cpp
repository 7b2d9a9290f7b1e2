// The C API's filters: settings by key, images, commit, execute and the memory query.
#include "capi/frame_assembly.h"
#include "core/closest_name.h"
#include <bmfr/bmfr.hpp>
#include <climits>
#include <cstdio>
#include <cstring>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace bmfr::capi {

namespace {

const char* const kConventions[] = {"accumulationMode", "frameIndex",           "jitterX",
                                    "jitterY",          "motionScaleX",         "motionScaleY",
                                    "motionYUp",        "motionIncludesJitter", "normalOctUnorm"};

BMFRFilterImpl& requireFilter(BMFRFilter filter) {
    if (!filter) throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "the filter handle is NULL"};
    return *filter;
}

BMFRDeviceImpl* deviceOf(BMFRFilter filter) {
    return filter ? filter->device : nullptr;
}

std::string_view requireName(const char* name, const char* what) {
    if (!name) throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, std::string(what) + " is NULL"};
    return name;
}

/// Every key the filter takes: its settings table's, the preset, the reservation and the
/// per-frame conventions.
std::vector<std::string> filterKeys(const BMFRFilterImpl& f) {
    std::vector<std::string> keys;
    for (const SettingDoc& d : filterSettings(f.type))
        if (d.key != "backend" && d.key != "threads") keys.push_back(d.key);
    keys.insert(keys.end(), {"preset", "maxWidth", "maxHeight"});
    for (const char* c : kConventions) keys.emplace_back(c);
    return keys;
}

bool isTableKey(const BMFRFilterImpl& f, std::string_view key) {
    for (const SettingDoc& d : filterSettings(f.type))
        if (d.key == key) {
            if (key == "backend" || key == "threads")
                throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                                   "'" + std::string(key) +
                                       "' is the device's: make a device of the type "
                                       "and threads you want (bmfrNewDevice)"};
            return true;
        }
    return false;
}

[[noreturn]] void unknownKey(const BMFRFilterImpl& f, std::string_view key) {
    const std::string name(key);
    throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "unknown setting '" + name + "' for filter " +
                                                        f.type + didYouMean(name, filterKeys(f))};
}

/// A setting of the filter's table, as text; the next commit applies it.
void setTableValue(BMFRFilterImpl& f, std::string_view key, const std::string& text) {
    if (!isTableKey(f, key)) unknownKey(f, key);
    for (auto& kv : f.values)
        if (kv.first == key) {
            kv.second = text;
            f.changed = true;
            return;
        }
    f.values.emplace_back(std::string(key), text);
    f.changed = true;
}

/// The value of a table key as text: as set, else as the preset gives it, else the default.
std::string tableValue(const BMFRFilterImpl& f, std::string_view key) {
    for (const auto& kv : f.values)
        if (kv.first == key) return kv.second;
    for (const auto& kv : presetSettings(f.type, f.preset))
        if (kv.first == key) return kv.second;
    for (const SettingDoc& d : filterSettings(f.type))
        if (d.key == key) return d.defaultValue;
    unknownKey(f, key);
}

[[noreturn]] void wrongType(std::string_view key, const char* type, const std::string& text) {
    throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "setting '" + std::string(key) + "' is not " +
                                                        type + " (its value is '" + text + "')"};
}

float& conventionFloat(BMFRFilterImpl& f, std::string_view key) {
    if (key == "jitterX") return f.frame.jitter[0];
    if (key == "jitterY") return f.frame.jitter[1];
    if (key == "motionScaleX") return f.frame.motion.scale[0];
    return f.frame.motion.scale[1];
}

bool& conventionBool(BMFRFilterImpl& f, std::string_view key) {
    if (key == "motionYUp") return f.frame.motion.yUp;
    if (key == "motionIncludesJitter") return f.frame.motion.includesJitter;
    return f.frame.normalOctUnorm;
}

bool isFloatConvention(std::string_view key) {
    return key == "jitterX" || key == "jitterY" || key == "motionScaleX" || key == "motionScaleY";
}

bool isBoolConvention(std::string_view key) {
    return key == "motionYUp" || key == "motionIncludesJitter" || key == "normalOctUnorm";
}

void setInt(BMFRFilterImpl& f, std::string_view key, long value) {
    if (key == "accumulationMode") {
        if (value < BMFR_ACCUMULATION_MODE_CONTINUE ||
            value > BMFR_ACCUMULATION_MODE_CLEAR_AND_RESTART)
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "accumulationMode " + std::to_string(value) +
                                   " is not a BMFR_ACCUMULATION_MODE_ value (0, 1 or 2)"};
        f.frame.accumulationMode = int(value);
    } else if (key == "frameIndex") {
        if (value < -1)
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "frameIndex " + std::to_string(value) + " is below -1"};
        f.frame.frameIndex = value;
    } else if (key == "maxWidth" || key == "maxHeight") {
        if (value < 0 || value > 65536)
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, std::string(key) + " " +
                                                                std::to_string(value) +
                                                                " is outside [0, 65536]"};
        (key == "maxWidth" ? f.maxWidth : f.maxHeight) = int(value);
        f.changed = true;
    } else if (isFloatConvention(key)) {
        conventionFloat(f, key) = float(value);
    } else if (isBoolConvention(key)) {
        conventionBool(f, key) = value != 0;
    } else {
        setTableValue(f, key, std::to_string(value));
    }
}

/// With a reservation committed, sizes the buffer that `image` is converted into for the largest
/// frame (motion for three channels, whatever its conventions become).
void reserveConversion(BMFRFilterImpl& f, std::string_view name, const SharedImage& image) {
    if (f.maxWidth == 0 || name == "output") return;
    const ImagePlan plan = planImage(name, image, f.frame);
    const int channels = name == "motion" ? 3 : plan.channels;
    if (channels == 0) return;
    auto buffer = f.converted.find(name);
    if (buffer == f.converted.end()) buffer = f.converted.emplace(std::string(name), 0).first;
    buffer->second.reserve(size_t(f.maxWidth) * size_t(f.maxHeight) * size_t(channels));
}

/// Bytes the process has taken from malloc: what a filter's buffers are made with.
size_t heapBytes() {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
    const struct mallinfo2 m = mallinfo2();
    return m.uordblks + m.hblkhd;
#else
    throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                       "bmfrGetFilterMemoryBytes needs glibc 2.33's mallinfo2, which this "
                       "platform lacks"};
#endif
}

SharedImage sharedImage(std::string_view key, void* ptr, BMFRFormat format, size_t width,
                        size_t height, size_t byteOffset, size_t pixelStride, size_t rowStride) {
    const auto name = [key] { return std::string(key); };
    SharedImage image;
    image.format = int(format);
    const int channels = image.channels();
    if (channels == 0)
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "image '" + name() + "': unknown format " +
                                                            std::to_string(int(format)) +
                                                            " (expected a BMFR_FORMAT_ value)"};
    if (width == 0 || height == 0 || width > INT_MAX || height > INT_MAX)
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                           "image '" + name() + "' is " + std::to_string(width) + "x" +
                               std::to_string(height) + ": each side must be 1 or more"};
    const size_t pixelBytes = size_t(channels) * formatChannelBytes(int(format));
    if (pixelStride == 0) pixelStride = pixelBytes;
    if (pixelStride < pixelBytes)
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "image '" + name() + "': bytePixelStride " +
                                                            std::to_string(pixelStride) +
                                                            " is less than a " +
                                                            formatName(int(format)) + " pixel (" +
                                                            std::to_string(pixelBytes) + " bytes)"};
    if (rowStride == 0) rowStride = width * pixelStride;
    if (rowStride < width * pixelStride)
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                           "image '" + name() + "': byteRowStride " + std::to_string(rowStride) +
                               " is less than a row (" + std::to_string(width * pixelStride) +
                               " bytes)"};
    image.data = static_cast<unsigned char*>(ptr) + byteOffset;
    image.width = int(width);
    image.height = int(height);
    image.pixelStride = pixelStride;
    image.rowStride = rowStride;
    return image;
}

} // namespace

bool isFrameConvention(std::string_view key) {
    for (const char* c : kConventions)
        if (key == c) return true;
    return false;
}

void commitFilter(BMFRFilterImpl& f) {
    if (!f.device->device)
        throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                           "the device is not committed: call bmfrCommitDevice first"};
    if ((f.maxWidth == 0) != (f.maxHeight == 0))
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                           "set both maxWidth and maxHeight, or neither (they are " +
                               std::to_string(f.maxWidth) + " and " + std::to_string(f.maxHeight) +
                               ")"};
    for (const auto& [name, image] : f.images) reserveConversion(f, name, image);
    SettingValues values = presetSettings(f.type, f.preset);
    values.insert(values.end(), f.values.begin(), f.values.end());
    Device& device = *f.device->device;
    const int keptWidth = device.reservedWidth(), keptHeight = device.reservedHeight();
    device.reserve(f.maxWidth, f.maxHeight); // for this filter only: restored below
    std::unique_ptr<Filter> made;
    try {
        made = device.makeFilter(f.type, values);
    } catch (...) {
        device.reserve(keptWidth, keptHeight);
        throw;
    }
    device.reserve(keptWidth, keptHeight);
    f.filter = std::move(made);
    f.committedValues = std::move(values);
    f.changed = false;
    f.previousFrameIndex = -1;
}

void executeFilter(BMFRFilterImpl& f) {
    if (!f.filter)
        throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                           "the filter is not committed: call bmfrCommitFilter first"};
    if (f.changed)
        throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                           "settings changed since bmfrCommitFilter: commit again (a new "
                           "history starts)"};
    const auto found = f.images.find("output");
    if (found == f.images.end()) throw Error("image 'output' is not set");
    const SharedImage& out = found->second;
    planImage("output", out, f.frame);
    const auto color = f.images.find("color");
    if (color != f.images.end() &&
        (color->second.width != out.width || color->second.height != out.height))
        throw Error("image 'output' is " + std::to_string(out.width) + "x" +
                    std::to_string(out.height) + ", 'color' is " +
                    std::to_string(color->second.width) + "x" +
                    std::to_string(color->second.height));
    const FrameInput& in = assembleFrame(f);
    if (readsInPlace(out)) {
        const ImageView v = inPlaceView(out);
        f.filter->denoise(in, MutableImageView{const_cast<float*>(v.data), v.width, v.height,
                                               v.channels, v.rowStride});
    } else {
        writeShared(f.filter->denoise(in), out);
    }
    f.previousJitter[0] = f.frame.jitter[0];
    f.previousJitter[1] = f.frame.jitter[1];
    f.previousFrameIndex = f.frame.frameIndex;
    f.frame.accumulationMode = BMFR_ACCUMULATION_MODE_CONTINUE;
}

size_t filterMemoryBytes(BMFRFilterImpl& f, int width, int height) {
    if (!f.filter)
        throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                           "the filter is not committed: call bmfrCommitFilter first"};
    if (width < 1 || height < 1)
        throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                           "bmfrGetFilterMemoryBytes(" + std::to_string(width) + ", " +
                               std::to_string(height) + "): each side must be 1 or more"};
    if (f.device->backend == Backend::Cuda)
        throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                           "bmfrGetFilterMemoryBytes counts host memory; the cuda device's "
                           "buffers are in device memory, which it does not measure yet"};
    // A probe: the same filter on a device of the same threads, sized for the frame. Its heap
    // growth is its buffers (and its few bookkeeping bytes).
    Device probe(f.device->backend, f.device->device->threadCount());
    probe.reserve(width, height);
    const size_t before = heapBytes();
    size_t bytes;
    {
        const std::unique_ptr<Filter> sized = probe.makeFilter(f.type, f.committedValues);
        const size_t after = heapBytes();
        if (after <= before)
            throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                               "bmfrGetFilterMemoryBytes reads glibc's heap statistics, which did "
                               "not move: this process allocates through another allocator (a "
                               "sanitizer's, or an operator new of its own)"};
        bytes = after - before;
    }
    for (const auto& [name, image] : f.images) {
        if (name == "output") continue;
        const ImagePlan plan = planImage(name, image, f.frame);
        bytes += size_t(width) * size_t(height) * size_t(plan.channels) * sizeof(float);
    }
    return bytes;
}

} // namespace bmfr::capi

using namespace bmfr::capi;

extern "C" {

BMFRFilter bmfrNewFilter(BMFRDevice device, const char* type) noexcept {
    return guard<BMFRFilter>(device, nullptr, [&]() -> BMFRFilter {
        if (!device) throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT, "the device handle is NULL"};
        const std::string name(requireName(type, "the filter type"));
        if (!device->device)
            throw BMFRApiError{BMFR_ERROR_INVALID_OPERATION,
                               "the device is not committed: call bmfrCommitDevice first"};
        bmfr::filterSettings(name); // an unknown name is an error now, with the known ones
        auto f = std::make_unique<BMFRFilterImpl>();
        f->type = name;
        f->device = device;
        device->references.fetch_add(1);
        return f.release();
    });
}

void bmfrRetainFilter(BMFRFilter filter) noexcept {
    guard(deviceOf(filter), 0, [&] {
        requireFilter(filter).references.fetch_add(1);
        return 0;
    });
}

void bmfrReleaseFilter(BMFRFilter filter) noexcept {
    guard(deviceOf(filter), 0, [&] {
        if (requireFilter(filter).references.fetch_sub(1) == 1) {
            BMFRDeviceImpl* device = filter->device;
            delete filter;
            bmfrReleaseDevice(device);
        }
        return 0;
    });
}

void bmfrSetFilterImage(BMFRFilter filter, const char* name, void* ptr, BMFRFormat format,
                        size_t width, size_t height, size_t byteOffset, size_t bytePixelStride,
                        size_t byteRowStride) noexcept {
    guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the image name");
        if (!isImageName(key)) {
            const std::string given(key);
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "unknown image '" + given + "'" +
                                   bmfr::didYouMean(given, imageNames())};
        }
        const auto found = f.images.find(key);
        if (!ptr) {
            if (found != f.images.end()) f.images.erase(found);
            return 0;
        }
        const SharedImage image = sharedImage(key, ptr, format, width, height, byteOffset,
                                              bytePixelStride, byteRowStride);
        // Names are looked up as given: re-setting an image each frame allocates nothing.
        if (found != f.images.end())
            found->second = image;
        else
            f.images.emplace(std::string(key), image);
        reserveConversion(f, key, image);
        return 0;
    });
}

void bmfrUnsetFilterImage(BMFRFilter filter, const char* name) noexcept {
    bmfrSetFilterImage(filter, name, nullptr, BMFR_FORMAT_UNDEFINED, 0, 0, 0, 0, 0);
}

void bmfrSetFilterMatrix(BMFRFilter filter, const char* name, const float* m) noexcept {
    guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the matrix name");
        if (key != "viewProjection")
            throw BMFRApiError{BMFR_ERROR_INVALID_ARGUMENT,
                               "unknown matrix '" + std::string(key) +
                                   "' (the filter takes viewProjection)"};
        if (!m) {
            f.frame.hasViewProjection = false;
            return 0;
        }
        for (int r = 0; r < 4; ++r)
            for (int c = 0; c < 4; ++c) f.frame.viewProjection.m[r][c] = m[4 * r + c];
        f.frame.hasViewProjection = true;
        return 0;
    });
}

void bmfrSetFilterBool(BMFRFilter filter, const char* name, bool value) noexcept {
    guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the setting name");
        if (isBoolConvention(key))
            conventionBool(f, key) = value;
        else if (isFrameConvention(key) || key == "preset" || key == "maxWidth" ||
                 key == "maxHeight")
            wrongType(key, "a bool", value ? "true" : "false");
        else
            setTableValue(f, key, value ? "true" : "false");
        return 0;
    });
}

void bmfrSetFilterInt(BMFRFilter filter, const char* name, int value) noexcept {
    guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        setInt(f, requireName(name, "the setting name"), value);
        return 0;
    });
}

void bmfrSetFilterFloat(BMFRFilter filter, const char* name, float value) noexcept {
    guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the setting name");
        if (isFloatConvention(key)) {
            conventionFloat(f, key) = value;
        } else if (isFrameConvention(key) || key == "maxWidth" || key == "maxHeight") {
            if (!(value >= -1e9f && value <= 1e9f) || value != float(long(value)))
                wrongType(key, "a whole number", std::to_string(value));
            setInt(f, key, long(value));
        } else {
            char text[32];
            std::snprintf(text, sizeof text, "%.9g", double(value));
            setTableValue(f, key, text);
        }
        return 0;
    });
}

void bmfrSetFilterString(BMFRFilter filter, const char* name, const char* value) noexcept {
    guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the setting name");
        const std::string text(requireName(value, "the value"));
        if (key == "preset") {
            bmfr::presetSettings(f.type, text); // an unknown preset is an error now
            f.preset = text;
            f.changed = true;
        } else if (isFrameConvention(key) || key == "maxWidth" || key == "maxHeight") {
            wrongType(key, "a string", text);
        } else {
            setTableValue(f, key, text);
        }
        return 0;
    });
}

bool bmfrGetFilterBool(BMFRFilter filter, const char* name) noexcept {
    return guard(deviceOf(filter), false, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the setting name");
        if (isBoolConvention(key)) return conventionBool(f, key);
        const std::string text = tableValue(f, key);
        if (text != "true" && text != "false") wrongType(key, "a bool", text);
        return text == "true";
    });
}

int bmfrGetFilterInt(BMFRFilter filter, const char* name) noexcept {
    return guard(deviceOf(filter), 0, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the setting name");
        if (key == "accumulationMode") return f.frame.accumulationMode;
        if (key == "frameIndex") return int(f.frame.frameIndex);
        if (key == "maxWidth") return f.maxWidth;
        if (key == "maxHeight") return f.maxHeight;
        const std::string text = tableValue(f, key);
        char* end = nullptr;
        const long v = std::strtol(text.c_str(), &end, 10);
        if (text.empty() || *end != '\0' || v < INT_MIN || v > INT_MAX)
            wrongType(key, "an int", text);
        return int(v);
    });
}

float bmfrGetFilterFloat(BMFRFilter filter, const char* name) noexcept {
    return guard(deviceOf(filter), 0.0f, [&] {
        BMFRFilterImpl& f = requireFilter(filter);
        const std::string_view key = requireName(name, "the setting name");
        if (isFloatConvention(key)) return conventionFloat(f, key);
        const std::string text = tableValue(f, key);
        char* end = nullptr;
        const float v = std::strtof(text.c_str(), &end);
        if (text.empty() || *end != '\0') wrongType(key, "a number", text);
        return v;
    });
}

void bmfrCommitFilter(BMFRFilter filter) noexcept {
    guard(deviceOf(filter), 0, [&] {
        commitFilter(requireFilter(filter));
        return 0;
    });
}

void bmfrExecuteFilter(BMFRFilter filter) noexcept {
    guard(deviceOf(filter), 0, [&] {
        executeFilter(requireFilter(filter));
        return 0;
    });
}

void bmfrExecuteFilterAsync(BMFRFilter filter) noexcept {
    // The images are host memory on every device, so the frame is done when this returns.
    bmfrExecuteFilter(filter);
}

size_t bmfrGetFilterMemoryBytes(BMFRFilter filter, int width, int height) noexcept {
    return guard(deviceOf(filter), size_t(0),
                 [&] { return filterMemoryBytes(requireFilter(filter), width, height); });
}

} // extern "C"
