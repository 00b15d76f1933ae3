import { launch } from '/work/wt-pol2/tests/browser/launch.mjs';
const [url] = process.argv.slice(2);
const { context, page, consoleErrors } = await launch('/tmp/pol2dbg');
page.on('console', (m) => console.log('console', m.type(), m.text()));
await page.goto(url);
await new Promise((r) => setTimeout(r, 8000));
console.log(JSON.stringify(await page.evaluate(() => ({ err: window.godelViewer && window.godelViewer.error, frames: window.godelViewer && window.godelViewer.frames }))));
console.log(JSON.stringify(consoleErrors));
await context.close();
