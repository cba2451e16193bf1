// Placeholder translation unit; replaced as the io area lands.
namespace adaptex {}
