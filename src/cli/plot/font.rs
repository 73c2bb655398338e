//! An 8 x 8 pixel font for the plots' numbers and labels: every printable ASCII
//! character, from the public-domain glyphs of the `font8x8` crate. Any other character is
//! drawn as an empty box, so that it shows rather than vanishing.

use font8x8::legacy::BASIC_LEGACY;
use image::{Rgb, RgbImage};

/// Glyph width in font pixels; the glyphs hold their own spacing.
pub const WIDTH: u32 = 8;
/// Glyph height in font pixels.
pub const HEIGHT: u32 = 8;

/// The box drawn for a character the font lacks: an outline inside the glyph cell.
const UNKNOWN: [u8; 8] = [0x00, 0x3f, 0x21, 0x21, 0x21, 0x21, 0x3f, 0x00];

/// The rows of `c`'s glyph, top first, the leftmost pixel in bit 0.
fn glyph(c: char) -> [u8; 8] {
    match c {
        ' '..='~' => BASIC_LEGACY[c as usize],
        _ => UNKNOWN,
    }
}

/// Pixels `text` spans horizontally at `scale` font pixels per glyph pixel.
pub fn text_width(text: &str, scale: u32) -> u32 {
    text.chars().count() as u32 * WIDTH * scale
}

/// Draws `text` with its top-left corner at `(x, y)`, each font pixel a `scale` x
/// `scale` square; what falls outside the image is clipped.
pub fn draw(image: &mut RgbImage, x: u32, y: u32, text: &str, scale: u32, colour: Rgb<u8>) {
    for (i, c) in text.chars().enumerate() {
        let left = x + i as u32 * WIDTH * scale;
        for (row, bits) in glyph(c).iter().enumerate() {
            for col in 0..WIDTH {
                if bits >> col & 1 == 0 {
                    continue;
                }
                for dy in 0..scale {
                    for dx in 0..scale {
                        let (px, py) = (left + col * scale + dx, y + row as u32 * scale + dy);
                        if px < image.width() && py < image.height() {
                            image.put_pixel(px, py, colour);
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const INK: Rgb<u8> = Rgb([0, 0, 0]);

    /// `text` drawn at scale 1 on a white strip just large enough for it.
    fn render(text: &str) -> RgbImage {
        let mut image = RgbImage::from_pixel(text_width(text, 1), HEIGHT, Rgb([255; 3]));
        draw(&mut image, 0, 0, text, 1, INK);
        image
    }

    /// Whether the glyph cell of the `i`th character holds ink.
    fn inked(image: &RgbImage, i: u32) -> bool {
        (0..HEIGHT).any(|y| (0..WIDTH).any(|x| *image.get_pixel(i * WIDTH + x, y) == INK))
    }

    #[test]
    fn every_letter_of_a_capitalised_word_is_drawn() {
        let image = render("Height");
        for i in 0..6 {
            assert!(inked(&image, i), "letter {i} of \"Height\" is blank");
        }
    }

    #[test]
    fn capitals_differ_from_small_letters() {
        assert_ne!(render("ABC"), render("abc"));
    }

    #[test]
    fn every_printable_character_and_an_unknown_one_show() {
        let printable: String = ('!'..='~').collect();
        let image = render(&printable);
        for i in 0..printable.len() as u32 {
            assert!(
                inked(&image, i),
                "{:?} is blank",
                printable.as_bytes()[i as usize]
            );
        }
        assert!(inked(&render("é"), 0));
        assert!(inked(&render("\t"), 0));
        assert!(!inked(&render(" "), 0));
    }
}
