// Placeholder translation unit; replaced as the adapt area lands.
namespace adaptex {}
