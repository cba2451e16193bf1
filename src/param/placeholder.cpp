// Placeholder translation unit; replaced as the param area lands.
namespace adaptex {}
